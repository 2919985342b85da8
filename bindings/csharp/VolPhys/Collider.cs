// A rigid collider by id (a value: copying it does not copy the body).
namespace VolPhys
{
    public struct Collider
    {
        public readonly vpColliderId Id;
        public Collider(vpColliderId id) { Id = id; }

        public static vpColliderDef DefaultDef() { return Native.vpDefaultColliderDef(); }
        public static vpShapeDef DefaultShapeDef() { return Native.vpDefaultShapeDef(); }

        public bool IsValid { get { return Native.vpColliderIsValid(Id) == Status.Ok; } }

        public vpTransform Pose
        {
            get { vpTransform t; VolPhysException.Check(Native.vpColliderGetPose(Id, out t), "vpColliderGetPose"); return t; }
            set { VolPhysException.Check(Native.vpColliderSetPose(Id, ref value), "vpColliderSetPose"); }
        }

        public BodyType BodyType
        {
            get { BodyType b; VolPhysException.Check(Native.vpColliderGetBodyType(Id, out b), "vpColliderGetBodyType"); return b; }
        }

        public void SetVelocity(vpVec3 linear, vpVec3 angular)
        {
            VolPhysException.Check(Native.vpColliderSetVelocity(Id, linear, angular), "vpColliderSetVelocity");
        }

        public void SetKinematicTarget(vpTransform target)
        {
            VolPhysException.Check(Native.vpColliderSetKinematicTarget(Id, ref target), "vpColliderSetKinematicTarget");
        }

        public void Destroy() { VolPhysException.Check(Native.vpColliderDestroy(Id), "vpColliderDestroy"); }
    }
}
