"""Collider: a handle (vpColliderId) to a rigid body of a World."""
from collections import namedtuple
import ctypes

from . import _arrays
from . import _types as T
from ._api import call
from ._handle import ActorHandle

# position (x, y, z) and rotation quaternion (x, y, z, w), as in vpTransform.
Transform = namedtuple("Transform", "position rotation")
IDENTITY_ROTATION = (0.0, 0.0, 0.0, 1.0)


def make_transform(position, rotation=IDENTITY_ROTATION):
    return T.vpTransform(_arrays.vec3(position), _arrays.quat(rotation))


def transform_tuple(t):
    p, q = t.position, t.rotation
    return Transform((p.x, p.y, p.z), (q.x, q.y, q.z, q.w))


class Collider(ActorHandle):
    _is_valid_function = "vpColliderIsValid"
    _destroy_function = "vpColliderDestroy"

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

    @property
    def body_type(self):
        bt = T.c_enum()
        call("vpColliderGetBodyType", self._id, ctypes.byref(bt))
        return T.BodyType(bt.value)

    def shape_mesh(self):
        """The shape as a triangle mesh in the collider's local frame, for drawing:
        (positions (v,3) float32, normals (v,3) float32, triangles (t,3) int32)."""
        return self._read_mesh("vpColliderGetShapeMeshSize", "vpColliderGetShapeMesh")
