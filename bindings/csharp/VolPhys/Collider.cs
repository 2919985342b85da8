// A rigid collider by id (a value: copying it does not copy the body).
using System;
using System.Runtime.InteropServices;

namespace VolPhys
{
    public struct Collider
    {
        public readonly vpColliderId Id;
        public Collider(vpColliderId id) { Id = id; }

        public static vpColliderDef DefaultDef() { return Native.vpDefaultColliderDef(); }
        public static vpShapeDef DefaultShapeDef() { return Native.vpDefaultShapeDef(); }

        public bool IsValid { get { return Native.vpColliderIsValid(Id) == Status.Ok; } }
        /// <summary>The name its scene file gave it ("" when none).</summary>
        public string Name
        {
            get { var id = Id; return ActorName.Read((byte[] b, int c, out int l) => Native.vpColliderGetName(id, b, c, out l), "vpColliderGetName"); }
        }

        /// <summary>Which colliders it meets; a change takes effect from the next step.</summary>
        public vpCollisionFilter CollisionFilter
        {
            get { vpCollisionFilter f; VolPhysException.Check(Native.vpColliderGetCollisionFilter(Id, out f), "vpColliderGetCollisionFilter"); return f; }
            set { VolPhysException.Check(Native.vpColliderSetCollisionFilter(Id, value), "vpColliderSetCollisionFilter"); }
        }

        public vpTransform Pose
        {
            get { vpTransform t; VolPhysException.Check(Native.vpColliderGetPose(Id, out t), "vpColliderGetPose"); return t; }
            set { VolPhysException.Check(Native.vpColliderSetPose(Id, ref value), "vpColliderSetPose"); }
        }

        public BodyType BodyType
        {
            get { BodyType b; VolPhysException.Check(Native.vpColliderGetBodyType(Id, out b), "vpColliderGetBodyType"); return b; }
        }

        public void GetVelocity(out vpVec3 linear, out vpVec3 angular)
        {
            VolPhysException.Check(Native.vpColliderGetVelocity(Id, out linear, out angular), "vpColliderGetVelocity");
        }

        public void SetVelocity(vpVec3 linear, vpVec3 angular)
        {
            VolPhysException.Check(Native.vpColliderSetVelocity(Id, linear, angular), "vpColliderSetVelocity");
        }

        public void SetKinematicTarget(vpTransform target)
        {
            VolPhysException.Check(Native.vpColliderSetKinematicTarget(Id, ref target), "vpColliderSetKinematicTarget");
        }

        // Pushing a dynamic body: a force or torque acts during the whole next step, an impulse at
        // once; `point` is in world space, null for the centre of mass.
        public void ApplyForce(vpVec3 force, vpVec3? point = null)
        {
            vpVec3 p = point.GetValueOrDefault();
            VolPhysException.Check(point.HasValue ? Native.vpColliderApplyForce(Id, force, ref p)
                                                  : Native.vpColliderApplyForce(Id, force, IntPtr.Zero), "vpColliderApplyForce");
        }

        public void ApplyTorque(vpVec3 torque)
        {
            VolPhysException.Check(Native.vpColliderApplyTorque(Id, torque), "vpColliderApplyTorque");
        }

        public void ApplyImpulse(vpVec3 impulse, vpVec3? point = null)
        {
            vpVec3 p = point.GetValueOrDefault();
            VolPhysException.Check(point.HasValue ? Native.vpColliderApplyImpulse(Id, impulse, ref p)
                                                  : Native.vpColliderApplyImpulse(Id, impulse, IntPtr.Zero), "vpColliderApplyImpulse");
        }

        public void ApplyAngularImpulse(vpVec3 angularImpulse)
        {
            VolPhysException.Check(Native.vpColliderApplyAngularImpulse(Id, angularImpulse), "vpColliderApplyAngularImpulse");
        }

        // Mass (dynamic bodies), friction, restitution and damping; a failed set changes nothing.
        public vpBodyProperties Properties
        {
            get
            {
                vpBodyProperties p = new vpBodyProperties { structSize = (uint)Marshal.SizeOf(typeof(vpBodyProperties)) };
                VolPhysException.Check(Native.vpColliderGetProperties(Id, ref p), "vpColliderGetProperties");
                return p;
            }
            set
            {
                value.structSize = (uint)Marshal.SizeOf(typeof(vpBodyProperties));
                VolPhysException.Check(Native.vpColliderSetProperties(Id, ref value), "vpColliderSetProperties");
            }
        }

        public bool Sleeping
        {
            get { int s; VolPhysException.Check(Native.vpColliderIsSleeping(Id, out s), "vpColliderIsSleeping"); return s != 0; }
            set { VolPhysException.Check(Native.vpColliderSetSleeping(Id, value ? 1 : 0), "vpColliderSetSleeping"); }
        }

        public void Destroy() { VolPhysException.Check(Native.vpColliderDestroy(Id), "vpColliderDestroy"); }
    }
}
