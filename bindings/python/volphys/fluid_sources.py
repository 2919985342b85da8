"""Where a fluid starts, enters and leaves: regions (box, sphere) and emitters, turned into
vpFluidRegion / vpFluidEmitter when a fluid is created. Coordinates are world space."""
import abc

from . import _arrays
from . import _types as T


class Region(abc.ABC):
    """Base of BoxRegion and SphereRegion."""

    @abc.abstractmethod
    def _to_c(self):
        """The vpFluidRegion this region becomes."""


class BoxRegion(Region):
    """An axis-aligned box: centre and half extents."""

    def __init__(self, centre, half_extents):
        self.centre, self.half_extents = tuple(centre), tuple(half_extents)

    def __repr__(self):
        return "BoxRegion(%r, %r)" % (self.centre, self.half_extents)

    def _to_c(self):
        return T.vpFluidRegion(type=int(T.RegionType.Box), centre=_arrays.vec3(self.centre),
                               halfExtents=_arrays.vec3(self.half_extents))


class SphereRegion(Region):
    def __init__(self, centre, radius):
        self.centre, self.radius = tuple(centre), float(radius)

    def __repr__(self):
        return "SphereRegion(%r, %r)" % (self.centre, self.radius)

    def _to_c(self):
        return T.vpFluidRegion(type=int(T.RegionType.Sphere), centre=_arrays.vec3(self.centre), radius=self.radius)


class Emitter:
    """Smoke: adds density_rate * dt of smoke per step in `region`, sets its temperature and
    the fluid's velocity there. Liquid: keeps `region` full of liquid moving with `velocity`.
    The defaults (rate 1, temperature 1) are those of scene files."""

    def __init__(self, region, velocity=(0.0, 0.0, 0.0), density_rate=1.0, temperature=1.0):
        self.region, self.velocity = region, tuple(velocity)
        self.density_rate, self.temperature = float(density_rate), float(temperature)

    def __repr__(self):
        return "Emitter(%r, velocity=%r, density_rate=%r, temperature=%r)" % (
            self.region, self.velocity, self.density_rate, self.temperature)

    def _to_c(self):
        return T.vpFluidEmitter(region=_region_to_c(self.region), velocity=_arrays.vec3(self.velocity),
                                densityRate=self.density_rate, temperature=self.temperature)


def _region_to_c(region):
    # Raw ctypes structs pass through, so hosts holding vpFluidRegion values need no wrapper.
    return region if isinstance(region, T.vpFluidRegion) else region._to_c()


def _emitter_to_c(emitter):
    return emitter if isinstance(emitter, T.vpFluidEmitter) else emitter._to_c()


def region_array(regions):
    """A C array of vpFluidRegion (the keepalive and pointer are the same object) and its length."""
    items = [_region_to_c(r) for r in regions or ()]
    return (T.vpFluidRegion * max(len(items), 1))(*items), len(items)


def emitter_array(emitters):
    items = [_emitter_to_c(e) for e in emitters or ()]
    return (T.vpFluidEmitter * max(len(items), 1))(*items), len(items)
