"""Collider: a handle (vpColliderId) to a rigid body of a World."""
from collections import namedtuple
import ctypes

from . import _arrays
from . import _types as T
from ._api import call
from . import _settings
from ._handle import ActorHandle

# position (x, y, z) and rotation quaternion (x, y, z, w), as in vpTransform.
Transform = namedtuple("Transform", "position rotation")
# vpBodyProperties without its structSize; mass is 0 for static and kinematic bodies.
BodyProperties = namedtuple("BodyProperties", "mass friction restitution linear_damping angular_damping")


def _point_ref(point):
    return None if point is None else ctypes.byref(_arrays.vec3(point))
IDENTITY_ROTATION = (0.0, 0.0, 0.0, 1.0)


def make_transform(position, rotation=IDENTITY_ROTATION):
    return T.vpTransform(_arrays.vec3(position), _arrays.quat(rotation))


def transform_tuple(t):
    p, q = t.position, t.rotation
    return Transform((p.x, p.y, p.z), (q.x, q.y, q.z, q.w))


class Collider(ActorHandle):
    _is_valid_function = "vpColliderIsValid"
    _destroy_function = "vpColliderDestroy"
    _name_function = "vpColliderGetName"
    _get_filter_function = "vpColliderGetCollisionFilter"
    _set_filter_function = "vpColliderSetCollisionFilter"

    @property
    def pose(self):
        t = T.vpTransform()
        call("vpColliderGetPose", self._id, ctypes.byref(t))
        return transform_tuple(t)

    @pose.setter
    def pose(self, value):
        self.set_pose(*value)

    def set_pose(self, position, rotation=IDENTITY_ROTATION):
        """Teleports the body; clears a pending kinematic target."""
        t = make_transform(position, rotation)
        call("vpColliderSetPose", self._id, ctypes.byref(t))

    @property
    def position(self):
        return self.pose.position

    @property
    def velocity(self):
        """(linear, angular)."""
        lin, ang = T.vpVec3(), T.vpVec3()
        call("vpColliderGetVelocity", self._id, ctypes.byref(lin), ctypes.byref(ang))
        return (lin.x, lin.y, lin.z), (ang.x, ang.y, ang.z)

    @velocity.setter
    def velocity(self, value):
        self.set_velocity(*value)

    def set_velocity(self, linear, angular=(0.0, 0.0, 0.0)):
        call("vpColliderSetVelocity", self._id, _arrays.vec3(linear), _arrays.vec3(angular))

    def set_kinematic_target(self, position, rotation=IDENTITY_ROTATION):
        t = make_transform(position, rotation)
        call("vpColliderSetKinematicTarget", self._id, ctypes.byref(t))

    # Pushing a dynamic body (the others raise InvalidArgumentError). A force or torque acts
    # during the whole next step, then is cleared; an impulse changes the velocity at once.
    # `point` is in world space; None is the centre of mass.
    def apply_force(self, force, point=None):
        call("vpColliderApplyForce", self._id, _arrays.vec3(force), _point_ref(point))

    def apply_torque(self, torque):
        call("vpColliderApplyTorque", self._id, _arrays.vec3(torque))

    def apply_impulse(self, impulse, point=None):
        call("vpColliderApplyImpulse", self._id, _arrays.vec3(impulse), _point_ref(point))

    def apply_angular_impulse(self, angular_impulse):
        call("vpColliderApplyAngularImpulse", self._id, _arrays.vec3(angular_impulse))

    @property
    def properties(self):
        """BodyProperties(mass, friction, restitution, linear_damping, angular_damping)."""
        return _settings.read("vpColliderGetProperties", self._id, T.vpBodyProperties, BodyProperties)

    def set_properties(self, **changes):
        """Changes some of BodyProperties' fields by name (validated as at creation; a
        failure changes nothing), e.g. set_properties(mass=3, friction=0.8)."""
        _settings.change("vpColliderGetProperties", "vpColliderSetProperties", self._id, T.vpBodyProperties,
                         BodyProperties, changes)

    @property
    def sleeping(self):
        s = ctypes.c_int32()
        call("vpColliderIsSleeping", self._id, ctypes.byref(s))
        return bool(s.value)

    @sleeping.setter
    def sleeping(self, value):
        call("vpColliderSetSleeping", self._id, 1 if value else 0)

    @property
    def body_type(self):
        bt = T.c_enum()
        call("vpColliderGetBodyType", self._id, ctypes.byref(bt))
        return T.BodyType(bt.value)

    def shape_mesh(self):
        """The shape as a triangle mesh in the collider's local frame, for drawing:
        (positions (v,3) float32, normals (v,3) float32, triangles (t,3) int32)."""
        return self._read_mesh("vpColliderGetShapeMeshSize", "vpColliderGetShapeMesh")
