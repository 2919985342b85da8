// An actor's scene name through the C ABI's length-then-copy pair (vpColliderGetName and its
// deformable and fluid twins), as UTF-8.
using System;
using System.Text;

namespace VolPhys
{
    internal delegate Status NameGetter(byte[] buffer, int capacity, out int length);

    internal static class ActorName
    {
        public static string Read(NameGetter get, string function)
        {
            int length;
            VolPhysException.Check(get(null, 0, out length), function);
            var buffer = new byte[length];
            VolPhysException.Check(get(buffer, length, out length), function);
            return Encoding.UTF8.GetString(buffer, 0, Math.Max(0, length - 1));
        }
    }
}
