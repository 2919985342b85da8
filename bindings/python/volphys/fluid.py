"""Fluid: a handle (vpFluidId) to a smoke or liquid actor on a MAC grid of a World.

Grids come back as numpy arrays indexed [k, j, i] (shape (nz, ny, nx), x fastest as in the C
layout, so no copy or transpose is made); without numpy, as flat lists in the C order."""
from collections import namedtuple
import ctypes
from ctypes import c_float, c_int32

from . import _arrays
from . import _types as T
from ._api import call, lib
from . import _settings
from ._handle import ActorHandle
from .stats import ActorStats


# vpFluidParameters without its structSize.
FluidParameters = namedtuple("FluidParameters", "ambient_temperature density_buoyancy thermal_buoyancy "
                             "vorticity_confinement density_dissipation temperature_dissipation kinematic_viscosity "
                             "sides")


class Fluid(ActorHandle):
    _is_valid_function = "vpFluidIsValid"
    _destroy_function = "vpFluidDestroy"
    _name_function = "vpFluidGetName"
    _get_filter_function = "vpFluidGetCollisionFilter"
    _set_filter_function = "vpFluidSetCollisionFilter"

    @property
    def resolution(self):
        """(nx, ny, nz) cells."""
        nx, ny, nz = c_int32(), c_int32(), c_int32()
        call("vpFluidGetResolution", self._id, ctypes.byref(nx), ctypes.byref(ny), ctypes.byref(nz))
        return nx.value, ny.value, nz.value

    @property
    def kind(self):
        """volphys.FluidKind.Smoke or .Liquid."""
        k = T.c_enum()
        call("vpFluidGetKind", self._id, ctypes.byref(k))
        return T.FluidKind(k.value)

    @property
    def domain(self):
        """(origin (x, y, z) of the low corner, cell size in metres)."""
        origin, h = T.vpVec3(), c_float()
        call("vpFluidGetDomain", self._id, ctypes.byref(origin), ctypes.byref(h))
        return (origin.x, origin.y, origin.z), h.value

    def _grid(self, width, fill):
        nx, ny, nz = self.resolution
        cells = nx * ny * nz
        out = _arrays.OutBuffer(cells, width, c_float)
        fill(out.ptr, cells)
        return _arrays.grid_result(out, (nz, ny, nx))

    def field(self, which):
        """A cell-centred field (volphys.FluidField or its name: 'smoke_density',
        'temperature', 'level_set', 'pressure'), float32 (nz, ny, nx)."""
        which = _field(which)
        return self._grid(1, lambda ptr, cells: call("vpFluidGetField", self._id, int(which), ptr, cells))

    def smoke_density(self):
        return self.field(T.FluidField.SmokeDensity)

    def temperature(self):
        return self.field(T.FluidField.Temperature)

    def level_set(self):
        """Liquid: signed distance, negative inside the liquid."""
        return self.field(T.FluidField.LevelSet)

    def pressure(self):
        return self.field(T.FluidField.Pressure)

    def velocity_grid(self):
        """Velocity at the cell centres, float32 (nz, ny, nx, 3)."""
        return self._grid(3, lambda ptr, cells: call("vpFluidGetVelocityGrid", self._id, ptr, cells))

    def sample_velocity(self, points):
        """Velocity at world points (n, 3) -> (n, 3) float32; trilinear, clamped to the domain."""
        ptr, n, keep = _arrays.floats3(points, "points")
        out = _arrays.OutBuffer(n, 3, c_float)
        # vpVec3 is three packed floats, so the flat float arrays are vpVec3 arrays.
        call("vpFluidSampleVelocity", self._id, ctypes.cast(ptr, ctypes.POINTER(T.vpVec3)), n,
             ctypes.cast(out.ptr, ctypes.POINTER(T.vpVec3)))
        del keep
        return out.result()

    def surface_mesh(self):
        """Liquid free surface in world space: (positions (v,3) float32, normals (v,3) float32
        pointing out of the liquid, triangles (t,3) int32). Empty for smoke."""
        return self._read_mesh("vpFluidGetSurfaceMeshSize", "vpFluidGetSurfaceMesh")

    @property
    def amount(self):
        """Liquid: volume in m^3. Smoke: total smoke (density * m^3)."""
        a = c_float()
        call("vpFluidGetAmount", self._id, ctypes.byref(a))
        return a.value

    def stats(self):
        s = lib.vpDefaultActorStats()
        call("vpFluidGetStats", self._id, ctypes.byref(s))
        return ActorStats._from_c(s)

    @property
    def parameters(self):
        """FluidParameters as last set (they act from the next fluid step that begins)."""
        return _settings.read("vpFluidGetParameters", self._id, T.vpFluidParameters, FluidParameters)

    def set_parameters(self, **changes):
        _settings.change("vpFluidGetParameters", "vpFluidSetParameters", self._id, T.vpFluidParameters,
                         FluidParameters, changes)

    @property
    def emitter_count(self):
        n = c_int32()
        call("vpFluidGetEmitterCount", self._id, ctypes.byref(n))
        return n.value

    def set_emitter(self, index, enabled=True, density_rate=1.0, velocity=(0.0, 0.0, 0.0), temperature=1.0):
        """Emitter `index` on or off, with its rate, velocity and temperature (its region stays)."""
        call("vpFluidSetEmitter", self._id, int(index), 1 if enabled else 0, density_rate, _arrays.vec3(velocity),
             temperature)


def _field(which):
    if isinstance(which, str):
        try:
            return T.FluidField["".join(part.capitalize() for part in which.split("_"))]
        except KeyError:
            raise ValueError("field %r: expected 'smoke_density', 'temperature', 'level_set' or 'pressure'"
                             % which) from None
    return T.FluidField(which)
