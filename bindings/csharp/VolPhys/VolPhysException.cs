// Failures of the C ABI as exceptions: the status and vpGetLastError()'s message, which names
// the bad argument or field and its value. Read the message at once: it is thread-local and
// replaced by the next failing call.
using System;

namespace VolPhys
{
    public class VolPhysException : Exception
    {
        public Status Status { get; private set; }

        public VolPhysException(Status status, string function, string message)
            : base(string.Format("{0} failed ({1}): {2}", function, status, message))
        {
            Status = status;
        }

        /// <summary>Throws for any status but Ok.</summary>
        public static void Check(Status status, string function)
        {
            if (status != Status.Ok) throw new VolPhysException(status, function, Native.LastError());
        }
    }
}
