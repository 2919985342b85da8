"""World: owns colliders, deformables and fluids; steps them under a frame budget."""
from collections import namedtuple
import ctypes
from ctypes import c_int32

from . import _arrays
from . import _types as T
from ._api import call, encode_path, lib
from ._handle import c_filter
from .collider import Collider
from .deformable import Deformable
from .fluid import Fluid
from .fluid_sources import emitter_array, region_array
from . import queries

ContactEvent = namedtuple("ContactEvent", "type deformable collider node_count point normal")
from .stats import ActorStats, StepStats

# Python keyword -> vpColliderDef field, for the plain float fields.
_COLLIDER_SCALARS = {
    "mass": "mass", "friction": "friction", "restitution": "restitution",
    "linear_damping": "linearDamping", "angular_damping": "angularDamping",
}
_DEFORMABLE_SCALARS = {
    "degree": "degree", "voxel_resolution": "voxelResolution", "youngs_modulus": "youngsModulus",
    "poisson_ratio": "poissonRatio", "density": "density", "mass_damping": "massDamping",
    "stiffness_damping": "stiffnessDamping", "friction": "friction", "solver_tolerance": "solverTolerance",
    "solver_max_iterations": "solverMaxIterations", "target_residual": "targetResidual", "priority": "priority",
    "mesh_grading": "meshGrading",
}

_FLUID_SCALARS = {
    "cell_size": "cellSize", "density": "density", "kinematic_viscosity": "kinematicViscosity",
    "cfl_number": "cflNumber", "max_substeps": "maxSubsteps",
    "pressure_tolerance": "pressureTolerance", "pressure_max_iterations": "pressureMaxIterations",
    "ambient_temperature": "ambientTemperature", "density_buoyancy": "densityBuoyancy",
    "thermal_buoyancy": "thermalBuoyancy", "vorticity_confinement": "vorticityConfinement",
    "density_dissipation": "densityDissipation", "temperature_dissipation": "temperatureDissipation",
    "two_way_coupling": "twoWayCoupling", "priority": "priority",
}
_SIDE_NAMES = ("-x", "+x", "-y", "+y", "-z", "+z")


def _enum_value(enum_type, value, what):
    # Strings name members case-insensitively ("liquid", "open", "semi_lagrangian").
    if isinstance(value, str):
        key = value.replace("_", "").lower()
        for member in enum_type:
            if member.name.lower() == key:
                return int(member)
        raise ValueError("%s %r: expected one of %s" % (what, value, ", ".join(repr(m.name.lower()) for m in enum_type)))
    return int(enum_type(value))


def _fill_sides(d, sides):
    """sides: six values in the order -x, +x, -y, +y, -z, +z, or a dict from those names to
    'wall' / 'open' (sides not named stay walls)."""
    if isinstance(sides, dict):
        unknown = set(sides) - set(_SIDE_NAMES)
        if unknown:
            raise ValueError("sides: unknown side(s) %s; expected %s" % (sorted(unknown), ", ".join(_SIDE_NAMES)))
        sides = [sides.get(name, T.DomainSide.Wall) for name in _SIDE_NAMES]
    sides = list(sides)
    if len(sides) != 6:
        raise ValueError("sides: expected 6 values (-x, +x, -y, +y, -z, +z), got %d" % len(sides))
    for i, side in enumerate(sides):
        d.sides[i] = _enum_value(T.DomainSide, side, "sides[%d]" % i)


def _body_type(value):
    if isinstance(value, str):
        try:
            return T.BodyType[value.capitalize()]
        except KeyError:
            raise ValueError("body_type %r: expected 'static', 'kinematic' or 'dynamic'" % value) from None
    return T.BodyType(value)


def _default_body_type(shape, scalars):
    # A plane can only be static; mass=0 is the usual way engines say "does not move".
    if shape.type == T.ShapeType.Plane or scalars.get("mass") == 0:
        return T.BodyType.Static  # the library ignores a static body's mass
    return T.BodyType.Dynamic


def _set_scalars(d, table, kwargs):
    """Sets d's fields named by `table` from keywords; collision_filter (a CollisionFilter or a
    (category, mask) pair) is accepted by every def."""
    kwargs = dict(kwargs)
    collision_filter = kwargs.pop("collision_filter", None)
    if collision_filter is not None:
        d.filter = c_filter(collision_filter)
    for key, value in kwargs.items():
        if key not in table:
            raise TypeError("unexpected keyword argument %r" % key)
        if value is not None:
            setattr(d, table[key], value)


def _set_pose(d, position, rotation):
    if position is not None:
        d.pose.position = _arrays.vec3(position)
    if rotation is not None:
        d.pose.rotation = _arrays.quat(rotation)


class World:
    """A simulation world. Destroy it with destroy() or by leaving a `with` block; ids of its
    colliders, deformables and fluids go stale then (using them raises InvalidIdError).

    Arguments left as None keep vpDefaultWorldDef()'s values (gravity (0,-9.81,0), 1 worker,
    16 ms budget, 1/120 s rigid sub-step, deformables solved on the CPU; device=Device.Cuda or
    Device.Auto moves their solves to a CUDA device, README "The GPU path")."""

    def __init__(self, gravity=None, workers=None, frame_budget_ms=None, rigid_max_substep=None, device=None):
        d = lib.vpDefaultWorldDef()
        if gravity is not None:
            d.gravity = _arrays.vec3(gravity)
        if workers is not None:
            d.workerCount = workers
        if frame_budget_ms is not None:
            d.frameBudgetMs = frame_budget_ms
        if rigid_max_substep is not None:
            d.rigidMaxSubstep = rigid_max_substep
        if device is not None:
            d.device = int(device)
        self._id = T.vpWorldId()
        call("vpWorldCreate", ctypes.byref(d), ctypes.byref(self._id))
        self._destroyed = False

    def __repr__(self):
        return "World(index1=%d, generation=%d%s)" % (self._id.index1, self._id.generation,
                                                       ", destroyed" if self._destroyed else "")

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.destroy()

    @property
    def id(self):
        return self._id

    @property
    def is_valid(self):
        return lib.vpWorldIsValid(self._id) == 0

    def destroy(self):
        """Destroys the world and everything in it. A second call does nothing (like
        file.close()); every other method raises InvalidIdError afterwards."""
        if self._destroyed:
            return
        call("vpWorldDestroy", self._id)
        self._destroyed = True

    # -------------------------------------------------------------- settings
    @property
    def gravity(self):
        g = T.vpVec3()
        call("vpWorldGetGravity", self._id, ctypes.byref(g))
        return (g.x, g.y, g.z)

    @gravity.setter
    def gravity(self, value):
        call("vpWorldSetGravity", self._id, _arrays.vec3(value))

    def set_frame_budget(self, ms):
        """0 = unlimited."""
        call("vpWorldSetFrameBudget", self._id, ms)

    # -------------------------------------------------------------- stepping
    def step(self, dt):
        """Advances by dt seconds (0 < dt <= 1) and returns the step's StepStats."""
        call("vpWorldStep", self._id, dt)
        return self.stats()

    def load_scene(self, path):
        """Adds a JSON scene's colliders and actors. All-or-nothing."""
        call("vpWorldLoadScene", self._id, encode_path(path))

    def stats(self):
        s = lib.vpDefaultStepStats()
        call("vpWorldGetStepStats", self._id, ctypes.byref(s))
        return StepStats._from_c(s)

    def actor_stats(self):
        """Per-actor stats of the last step; entry 0 is the rigid pseudo-actor."""
        n = self.stats().actor_count
        out = []
        for i in range(n):
            s = lib.vpDefaultActorStats()
            call("vpWorldGetActorStats", self._id, i, ctypes.byref(s))
            out.append(ActorStats._from_c(s))
        return out

    def contact_events(self):
        """Deformable-collider contacts that began or ended in the last step: a list of
        ContactEvent(type, deformable, collider, node_count, point, normal)."""
        count = c_int32()
        call("vpWorldGetContactEvents", self._id, None, 0, ctypes.byref(count))
        events = (T.vpContactEvent * max(count.value, 1))()
        call("vpWorldGetContactEvents", self._id, events, count.value, ctypes.byref(count))
        v = lambda p: (p.x, p.y, p.z)
        return [ContactEvent(T.ContactEventType(e.type), Deformable(self, T.vpDeformableId.from_buffer_copy(e.deformable)),
                             Collider(self, T.vpColliderId.from_buffer_copy(e.collider)), e.nodeCount, v(e.point),
                             v(e.normal)) for e in events[:count.value]]

    # -------------------------------------------------------------- saved states
    def save_state(self):
        """Everything that evolves, as bytes (vpWorldSaveState: saving completes any fluid step
        in progress and rebuilds Bullet's caches; stepping after restore_state(saved) is bitwise
        the stepping after this call). One save: the buffer is sized from the last one."""
        size = ctypes.c_size_t(0)
        capacity = getattr(self, "_state_size", 0)
        while True:
            buffer = ctypes.create_string_buffer(max(capacity, 1))
            status = lib.vpWorldSaveState(self._id, buffer if capacity else None, capacity, ctypes.byref(size))
            if status == T.Status.Ok and capacity >= size.value:
                self._state_size = size.value
                return buffer.raw[:size.value]
            if status not in (T.Status.Ok, T.Status.InvalidArgument) or size.value <= capacity:
                call("vpWorldSaveState", self._id, buffer, capacity, ctypes.byref(size))  # raises
            capacity = size.value

    def restore_state(self, state):
        """Puts back a state from save_state(); a truncated, corrupted or foreign one raises
        (the world is unchanged)."""
        data = bytes(state)
        call("vpWorldRestoreState", self._id, data, len(data))

    # -------------------------------------------------------------- scene queries
    # kinds: QueryKind bits; collision_filter: (category, mask) the objects must meet. Hits are
    # volphys.queries.Hit tuples; see that module.
    def raycast(self, origin, direction, max_distance=1000.0, kinds=T.QueryKind.All, collision_filter=None):
        """The nearest hit along the ray, or None."""
        return queries.raycast(self, origin, direction, max_distance, kinds, collision_filter)

    def raycast_all(self, origin, direction, max_distance=1000.0, kinds=T.QueryKind.All, collision_filter=None):
        """Every object the ray hits (its nearest hit on each), nearest first."""
        return queries.raycast_all(self, origin, direction, max_distance, kinds, collision_filter)

    def raycast_batch(self, origins, directions, max_distance=1000.0, kinds=T.QueryKind.All, collision_filter=None):
        """Each ray's nearest hit or None, in one call."""
        return queries.raycast_batch(self, origins, directions, max_distance, kinds, collision_filter)

    def overlap_sphere(self, centre, radius, kinds=T.QueryKind.All, collision_filter=None):
        return queries.overlap_sphere(self, centre, radius, kinds, collision_filter)

    def overlap_box(self, centre, half_extents, rotation=(0.0, 0.0, 0.0, 1.0), kinds=T.QueryKind.All,
                    collision_filter=None):
        return queries.overlap_box(self, centre, half_extents, rotation, kinds, collision_filter)

    # -------------------------------------------------------------- colliders
    def _list(self, count_function, list_function, id_type, handle_type):
        # Every kind is listed by a count call and a fill call, in slot order.
        n = c_int32()
        call(count_function, self._id, ctypes.byref(n))
        ids = (id_type * max(n.value, 1))()
        got = c_int32()
        call(list_function, self._id, ids, n.value, ctypes.byref(got))
        return [handle_type(self, id_type.from_buffer_copy(ids[i])) for i in range(got.value)]

    def colliders(self):
        return self._list("vpWorldGetColliderCount", "vpWorldGetColliders", T.vpColliderId, Collider)

    def deformables(self):
        return self._list("vpWorldGetDeformableCount", "vpWorldGetDeformables", T.vpDeformableId, Deformable)

    def find_collider(self, name):
        """The first collider the scene named `name`; InvalidArgumentError if none."""
        cid = T.vpColliderId()
        call("vpWorldFindCollider", self._id, name.encode("utf-8"), ctypes.byref(cid))
        return Collider(self, cid)

    def create_collider(self, shape, body_type=None, position=None, rotation=None,
                        linear_velocity=None, angular_velocity=None, **scalars):
        """shape: a volphys.Shape (Sphere(...), Box(...), Plane(...), ...). body_type: BodyType
        or 'static' / 'kinematic' / 'dynamic'; when not given, a plane or a body of mass=0 is
        static and anything else dynamic. Further keywords: mass, friction, restitution,
        linear_damping, angular_damping, collision_filter ((category, mask)). Anything not given
        keeps vpDefaultColliderDef()'s value."""
        d = lib.vpDefaultColliderDef()
        if body_type is None:
            body_type = _default_body_type(shape, scalars)
        d.bodyType = int(_body_type(body_type))
        keep = shape._fill(d.shape)
        _set_pose(d, position, rotation)
        if linear_velocity is not None:
            d.linearVelocity = _arrays.vec3(linear_velocity)
        if angular_velocity is not None:
            d.angularVelocity = _arrays.vec3(angular_velocity)
        _set_scalars(d, _COLLIDER_SCALARS, scalars)
        cid = T.vpColliderId()
        call("vpColliderCreate", self._id, ctypes.byref(d), ctypes.byref(cid))
        del keep  # the arrays d pointed into lived until the library copied them
        return Collider(self, cid)

    # -------------------------------------------------------------- deformables
    def find_deformable(self, name):
        did = T.vpDeformableId()
        call("vpWorldFindDeformable", self._id, name.encode("utf-8"), ctypes.byref(did))
        return Deformable(self, did)

    def create_deformable(self, vertices=None, tets=None, tet_file=None, surface_file=None,
                          render_vertices=None, render_triangles=None, position=None, rotation=None,
                          linear_velocity=None, surface_mesher=None, self_collision=None, **scalars):
        """Exactly one mesh source: vertices (n,3) + tets (m,4), tet_file, or surface_file.
        surface_mesher: SurfaceMesher or 'stuffing' (the default) / 'voxel', how surface_file
        becomes tets; voxel_resolution: cells along its longest axis, for either mesher;
        mesh_grading: levels of coarsening inside the body for stuffing, 0..8 (0: uniform).
        self_collision: SelfCollision or 'auto' (the default: on for meshes with more than one
        layer of elements) / 'off' / 'on', contact of the deformable with itself.
        Further keywords: degree, voxel_resolution, youngs_modulus, poisson_ratio, density,
        mass_damping, stiffness_damping, friction, solver_tolerance, solver_max_iterations,
        target_residual (the accuracy floor of the implicit solve, in [solver_tolerance, 1]),
        priority (higher is served first when the frame budget is short), collision_filter
        ((category, mask): the colliders it contacts)."""
        d = lib.vpDefaultDeformableDef()
        keep = []
        if vertices is not None:
            d.vertices, d.vertexCount, k = _arrays.floats3(vertices, "vertices")
            keep.append(k)
        if tets is not None:
            d.tets, d.tetCount, k = _arrays.ints(tets, 4, "tets")
            keep.append(k)
        if tet_file is not None:
            b = encode_path(tet_file)
            d.tetFile = b
            keep.append(b)
        if surface_file is not None:
            b = encode_path(surface_file)
            d.surfaceFile = b
            keep.append(b)
        if render_vertices is not None:
            d.renderVertices, d.renderVertexCount, k = _arrays.floats3(render_vertices, "render_vertices")
            keep.append(k)
        if render_triangles is not None:
            d.renderTriangles, d.renderTriangleCount, k = _arrays.ints(render_triangles, 3, "render_triangles")
            keep.append(k)
        _set_pose(d, position, rotation)
        if linear_velocity is not None:
            d.linearVelocity = _arrays.vec3(linear_velocity)
        if surface_mesher is not None:
            d.surfaceMesher = _enum_value(T.SurfaceMesher, surface_mesher, "surface_mesher")
        if self_collision is not None:
            d.selfCollision = _enum_value(T.SelfCollision, self_collision, "self_collision")
        _set_scalars(d, _DEFORMABLE_SCALARS, scalars)
        did = T.vpDeformableId()
        call("vpDeformableCreate", self._id, ctypes.byref(d), ctypes.byref(did))
        del keep
        return Deformable(self, did)

    # -------------------------------------------------------------- fluids
    def fluids(self):
        return self._list("vpWorldGetFluidCount", "vpWorldGetFluids", T.vpFluidId, Fluid)

    def find_fluid(self, name):
        fid = T.vpFluidId()
        call("vpWorldFindFluid", self._id, name.encode("utf-8"), ctypes.byref(fid))
        return Fluid(self, fid)

    def create_fluid(self, kind="smoke", origin=None, resolution=None, sides=None, advection=None,
                     initial_liquid=(), emitters=(), drains=(), **scalars):
        """A smoke or liquid actor filling the box from `origin` (low corner) of `resolution`
        (nx, ny, nz) cells. kind: FluidKind or 'smoke' / 'liquid'. sides: see _fill_sides.
        advection: Advection or 'semi_lagrangian' / 'mac_cormack'. initial_liquid, drains:
        BoxRegion / SphereRegion; emitters: Emitter. Further keywords: cell_size, density,
        kinematic_viscosity, cfl_number, max_substeps, pressure_tolerance, pressure_max_iterations,
        ambient_temperature, density_buoyancy, thermal_buoyancy, vorticity_confinement,
        density_dissipation, temperature_dissipation, two_way_coupling, priority (higher is served
        first when the frame budget is short), collision_filter ((category, mask): the colliders
        that bound it). Anything not given keeps vpDefaultFluidDef()'s value."""
        d = lib.vpDefaultFluidDef()
        d.kind = _enum_value(T.FluidKind, kind, "kind")
        if origin is not None:
            d.origin = _arrays.vec3(origin)
        if resolution is not None:
            nx, ny, nz = (int(n) for n in resolution)
            d.resolution[0], d.resolution[1], d.resolution[2] = nx, ny, nz
        if sides is not None:
            _fill_sides(d, sides)
        if advection is not None:
            d.advection = _enum_value(T.Advection, advection, "advection")
        if "two_way_coupling" in scalars and scalars["two_way_coupling"] is not None:
            scalars["two_way_coupling"] = int(bool(scalars["two_way_coupling"]))
        _set_scalars(d, _FLUID_SCALARS, scalars)
        liquid, d.initialLiquidCount = region_array(initial_liquid)
        sources, d.emitterCount = emitter_array(emitters)
        sinks, d.drainCount = region_array(drains)
        d.initialLiquid = ctypes.cast(liquid, ctypes.POINTER(T.vpFluidRegion))
        d.emitters = ctypes.cast(sources, ctypes.POINTER(T.vpFluidEmitter))
        d.drains = ctypes.cast(sinks, ctypes.POINTER(T.vpFluidRegion))
        fid = T.vpFluidId()
        call("vpFluidCreate", self._id, ctypes.byref(d), ctypes.byref(fid))
        del liquid, sources, sinks  # the library copied the sources
        return Fluid(self, fid)
