"""Deformable: a handle (vpDeformableId) to a tetrahedral FEM volume of a World."""
from collections import namedtuple
import ctypes
from ctypes import c_float, c_int32

from . import _arrays
from . import _types as T
from ._api import call, lib
from . import _settings
from ._handle import ActorHandle
from .stats import ActorStats


# vpDeformableMaterial without its structSize.
Material = namedtuple("Material", "youngs_modulus poisson_ratio density mass_damping stiffness_damping friction")
# vpDeformableGetMeshQuality: dihedral angles in degrees, volumes in m^3.
MeshQuality = namedtuple("MeshQuality", "min_dihedral max_dihedral tet_volume surface_volume")


class Deformable(ActorHandle):
    _is_valid_function = "vpDeformableIsValid"
    _destroy_function = "vpDeformableDestroy"
    _name_function = "vpDeformableGetName"
    _get_filter_function = "vpDeformableGetCollisionFilter"
    _set_filter_function = "vpDeformableSetCollisionFilter"

    @property
    def node_count(self):
        n = c_int32()
        call("vpDeformableGetNodeCount", self._id, ctypes.byref(n))
        return n.value

    def _get_nodes(self, fn):
        n = self.node_count
        out = _arrays.OutBuffer(n, 3, c_float)
        call(fn, self._id, out.ptr, n)
        return out.result()

    def positions(self):
        """Node positions, (n, 3) float32 (world frame)."""
        return self._get_nodes("vpDeformableGetPositions")

    def velocities(self):
        return self._get_nodes("vpDeformableGetVelocities")

    def set_velocities(self, velocities):
        ptr, n, keep = _arrays.floats3(velocities, "velocities")
        call("vpDeformableSetVelocities", self._id, ptr, n)
        del keep  # held until here: C copied it

    def set_positions(self, positions, reset_velocities=False):
        """Teleports every node ((n, 3), n = node_count); the render mesh follows."""
        ptr, n, keep = _arrays.floats3(positions, "positions")
        call("vpDeformableSetPositions", self._id, ptr, n, 1 if reset_velocities else 0)
        del keep

    @property
    def material(self):
        return _settings.read("vpDeformableGetMaterial", self._id, T.vpDeformableMaterial, Material)

    def set_material(self, **changes):
        """Changes Material fields by name from the next step, e.g. set_material(youngs_modulus=2e6)."""
        _settings.change("vpDeformableGetMaterial", "vpDeformableSetMaterial", self._id, T.vpDeformableMaterial,
                         Material, changes)

    def apply_force(self, node, force):
        """Acts during the next step only."""
        call("vpDeformableApplyForce", self._id, int(node), _arrays.vec3(force))

    def apply_impulse(self, node, impulse):
        """Changes the node's velocity now."""
        call("vpDeformableApplyImpulse", self._id, int(node), _arrays.vec3(impulse))

    def pin(self, nodes):
        """Pinned nodes stay put until unpinned. All-or-nothing."""
        ptr, n, keep = _arrays.index_list(nodes, "nodes")
        call("vpDeformablePin", self._id, ptr, n)
        del keep

    def unpin(self, nodes):
        ptr, n, keep = _arrays.index_list(nodes, "nodes")
        call("vpDeformableUnpin", self._id, ptr, n)
        del keep

    def attach(self, nodes, collider):
        """The nodes follow `collider` rigidly from their current offset in its frame."""
        ptr, n, keep = _arrays.index_list(nodes, "nodes")
        call("vpDeformableAttach", self._id, ptr, n, collider.id)
        del keep

    def render_mesh(self):
        """(positions (v,3) float32, normals (v,3) float32, triangles (t,3) int32)."""
        return self._read_mesh("vpDeformableGetRenderMeshSize", "vpDeformableGetRenderMesh")

    def stats(self):
        s = lib.vpDefaultActorStats()
        call("vpDeformableGetStats", self._id, ctypes.byref(s))
        return ActorStats._from_c(s)

    def mesh_quality(self):
        """MeshQuality of the simulation mesh: its tets' dihedral angle range and their volume
        against the volume its render surface encloses."""
        out = [c_float() for _ in range(4)]
        call("vpDeformableGetMeshQuality", self._id, *[ctypes.byref(v) for v in out])
        return MeshQuality(*[v.value for v in out])

    def solve_static(self, max_iterations=100, tolerance=1e-4):
        """Moves the body to its static equilibrium (gravity, pins, attachments, forces applied
        for the next step, contacts with the colliders as they stand) and leaves it at rest
        there. Returns (iterations, relative residual); raises NotConvergedError, with the body
        unchanged, when it stops above the tolerance."""
        iterations, residual = ctypes.c_int32(), ctypes.c_float()
        call("vpDeformableSolveStatic", self._id, int(max_iterations), float(tolerance), ctypes.byref(iterations),
             ctypes.byref(residual))
        return iterations.value, residual.value
