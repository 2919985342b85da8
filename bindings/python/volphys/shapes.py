"""Collider shapes. A Shape records its parameters; _fill() writes them into a vpShapeDef
that started from vpDefaultShapeDef(), returning the arrays the def points into."""
from . import _arrays
from ._api import encode_path
from ._types import ShapeType


class Shape:
    def __init__(self, type, **params):
        self.type = ShapeType(type)
        self.params = params

    def __repr__(self):
        return "Shape(%s, %s)" % (self.type.name, ", ".join("%s=%r" % kv for kv in self.params.items()))

    def _fill(self, sd):
        """Fills the vpShapeDef `sd`; returns objects to keep alive until the C call returns."""
        keep = []
        p = self.params
        sd.type = int(self.type)
        if "radius" in p:
            sd.radius = p["radius"]
        if "half_height" in p:
            sd.halfHeight = p["half_height"]
        if "half_extents" in p:
            sd.halfExtents = _arrays.vec3(p["half_extents"])
        if "normal" in p:
            sd.normal = _arrays.vec3(p["normal"])
        if "offset" in p:
            sd.offset = p["offset"]
        if p.get("points") is not None:
            ptr, n, k = _arrays.floats3(p["points"], "points")
            sd.points, sd.pointCount = ptr, n
            keep.append(k)
        if p.get("indices") is not None:
            ptr, n, k = _arrays.ints(p["indices"], 3, "indices")
            sd.indices, sd.triangleCount = ptr, n
            keep.append(k)
        if p.get("mesh_file") is not None:
            b = encode_path(p["mesh_file"])
            sd.meshFile = b
            keep.append(b)
        if p.get("scale") is not None:
            sd.meshScale = _arrays.vec3(p["scale"])
        return keep


def Sphere(radius):
    return Shape(ShapeType.Sphere, radius=radius)


def Box(half_extents):
    return Shape(ShapeType.Box, half_extents=half_extents)


def Capsule(radius, half_height):
    """Cylindrical part of length 2*half_height along local Y, capped by hemispheres."""
    return Shape(ShapeType.Capsule, radius=radius, half_height=half_height)


def Cylinder(radius, half_height):
    return Shape(ShapeType.Cylinder, radius=radius, half_height=half_height)


def Plane(normal=(0.0, 1.0, 0.0), offset=0.0):
    """Solid where dot(normal, x) <= offset."""
    return Shape(ShapeType.Plane, normal=normal, offset=offset)


def ConvexHull(points, scale=None):
    return Shape(ShapeType.ConvexHull, points=points, scale=scale)


def TriangleMesh(points=None, indices=None, mesh_file=None, scale=None):
    """Either points (n,3) + indices (t,3), or a mesh_file assimp reads."""
    return Shape(ShapeType.TriangleMesh, points=points, indices=indices, mesh_file=mesh_file, scale=scale)
