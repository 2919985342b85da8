"""Scene queries (vpWorldRaycast and the rest): rays and overlaps against colliders,
deformables and liquids. World's raycast / raycast_all / raycast_batch / overlap_sphere /
overlap_box call these; each object is reported at most once (a ray's nearest hit on it)."""
from collections import namedtuple
import ctypes
import math

from . import _arrays
from . import _types as T
from ._api import call, lib
from ._handle import c_filter

# kind: HitKind; obj: the Collider, Deformable or Fluid hit. point, normal: (x, y, z).
# triangle, barycentric, nearest_node: the render triangle, its vertex weights and the
# simulation node nearest the hit, for deformables (-1 / zeros otherwise).
Hit = namedtuple("Hit", "kind obj distance point normal triangle barycentric nearest_node")


def _filter(kinds, collision_filter):
    f = lib.vpDefaultQueryFilter()
    f.kinds = int(kinds)
    if collision_filter is not None:
        f.filter = c_filter(collision_filter)
    return f


def _ray(origin, direction, max_distance):
    # Unlike the C call, any non-zero direction is accepted (it is normalized here).
    d = tuple(float(x) for x in direction)
    n = math.sqrt(sum(x * x for x in d))
    if n > 0.0:
        d = tuple(x / n for x in d)
    return T.vpRay(_arrays.vec3(origin), _arrays.vec3(d), max_distance)


def _hit(world, h):
    from .collider import Collider
    from .deformable import Deformable
    from .fluid import Fluid
    kind = T.HitKind(h.kind)
    if kind == T.HitKind.NoHit:
        return None
    obj = {T.HitKind.Collider: lambda: Collider(world, T.vpColliderId.from_buffer_copy(h.collider)),
           T.HitKind.Deformable: lambda: Deformable(world, T.vpDeformableId.from_buffer_copy(h.deformable)),
           T.HitKind.Liquid: lambda: Fluid(world, T.vpFluidId.from_buffer_copy(h.fluid))}[kind]()
    v = lambda p: (p.x, p.y, p.z)
    return Hit(kind, obj, h.distance, v(h.point), v(h.normal), h.triangle, v(h.barycentric), h.nearestNode)


def _collect(world, fill):
    """Calls fill(buffer, capacity, count_ref) until the buffer holds every hit."""
    capacity = 8
    while True:
        hits = (T.vpQueryHit * capacity)()
        count = ctypes.c_int32()
        fill(hits, capacity, ctypes.byref(count))
        if count.value <= capacity:
            return [_hit(world, hits[i]) for i in range(count.value)]
        capacity = count.value


def raycast(world, origin, direction, max_distance, kinds, collision_filter):
    r, f = _ray(origin, direction, max_distance), _filter(kinds, collision_filter)
    hit, count = T.vpQueryHit(), ctypes.c_int32()
    call("vpWorldRaycast", world.id, ctypes.byref(r), ctypes.byref(f), ctypes.byref(hit), ctypes.byref(count))
    return _hit(world, hit) if count.value else None


def raycast_all(world, origin, direction, max_distance, kinds, collision_filter):
    r, f = _ray(origin, direction, max_distance), _filter(kinds, collision_filter)
    return _collect(world, lambda hits, n, count: call("vpWorldRaycastAll", world.id, ctypes.byref(r),
                                                         ctypes.byref(f), hits, n, count))


def raycast_batch(world, origins, directions, max_distance, kinds, collision_filter):
    rays = [_ray(o, d, max_distance) for o, d in zip(origins, directions)]
    if len(rays) != len(origins) or len(rays) != len(directions):
        raise ValueError("raycast_batch: origins and directions must have the same length")
    arr = (T.vpRay * max(len(rays), 1))(*rays)
    out = (T.vpQueryHit * max(len(rays), 1))()
    f = _filter(kinds, collision_filter)
    call("vpWorldRaycastBatch", world.id, arr, len(rays), ctypes.byref(f), out)
    return [_hit(world, out[i]) for i in range(len(rays))]


def overlap_sphere(world, centre, radius, kinds, collision_filter):
    f = _filter(kinds, collision_filter)
    c = _arrays.vec3(centre)
    return _collect(world, lambda hits, n, count: call("vpWorldOverlapSphere", world.id, c, radius, ctypes.byref(f),
                                                         hits, n, count))


def overlap_box(world, centre, half_extents, rotation, kinds, collision_filter):
    f = _filter(kinds, collision_filter)
    pose = T.vpTransform(_arrays.vec3(centre), _arrays.quat(rotation))
    h = _arrays.vec3(half_extents)
    return _collect(world, lambda hits, n, count: call("vpWorldOverlapBox", world.id, ctypes.byref(pose), h,
                                                         ctypes.byref(f), hits, n, count))
