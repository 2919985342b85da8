// Everything needed to create a deformable volume actor: the simulation mesh, the material,
// damping and solver settings. The C ABI and scene files both fill this in; the mesh is
// already loaded (arrays, tet files or a tetrahedralized surface) by then.
#pragma once

#include <optional>
#include <string>

#include "core/collision_filter.h"
#include "core/math_types.h"
#include "core/status.h"
#include "geometry/surface_mesh.h"
#include "geometry/tet_mesh.h"

namespace vp {

struct DeformableMaterial {
  double youngsModulus = 1e6;   // Pa
  double poissonRatio = 0.3;    // (-1, 0.5)
  double density = 1000.0;      // kg/m^3
  double massDamping = 0.0;     // Rayleigh alpha, 1/s
  double stiffnessDamping = 0.01;  // Rayleigh beta, s: damps fast modes, keeps slow ones
  double friction = 0.5;        // Coulomb coefficient against colliders

  double lameMu() const { return youngsModulus / (2.0 * (1.0 + poissonRatio)); }
  double lameLambda() const {
    return youngsModulus * poissonRatio / ((1.0 + poissonRatio) * (1.0 - 2.0 * poissonRatio));
  }
};

// Auto's choice for degree >= 2 was measured: on the 5184-tet cubic beam PCG to 1e-6 takes
// 16 iterations with p-multigrid against 57 with aggregation multigrid on the cubic matrix
// (BM_DeformSolve/{pmg_pcg,amg_pcg}/cubic, ~1.5x less time), and the 13056-tet quadratic
// beam's steps 8.5 against 20 (BM_DeformQuadraticBeam{,AggregationMultigrid}/13000).
enum class Preconditioner : int {
  Auto = 0,         // above kMultigridMinNodes nodes p-multigrid for degree >= 2, aggregation
                    // multigrid for degree 1; block-Jacobi below
  BlockJacobi = 1,
  Multigrid = 2,    // aggregation multigrid with rigid-body modes (linalg/aggregation_multigrid.h)
  PMultigrid = 3,   // V-cycle over the degrees, aggregation multigrid on the linear level
                    // (linalg/p_multigrid.h); degree 1 has no lower degree and gets Multigrid
};

// Below this many nodes the multigrid's setup costs more than the CG iterations it saves. A
// body in contact pays the setup again after every contact pass that changes its constraints:
// the default scene's duck jelly, then voxelized (711 nodes, linear), took 10.6 ms per frame
// with aggregation multigrid (90 CG iterations) and 7.7 ms with block-Jacobi (234), median of
// 120 frames each, run one after the other on the loaded 2-core machine; hence 1000 rather
// than the 400 that a contact-free beam suggested.
constexpr int kMultigridMinNodes = 1000;

// How p-multigrid gets its coarse operators. Re-discretized is the default: 0-4% more CG
// iterations than Galerkin, a half to a third less setup (measured in linalg/p_multigrid.h).
enum class PMultigridCoarseOperator : int {
  Galerkin = 0,       // P̃ᵀ A P̃ with the constrained prolongation
  Rediscretized = 1,  // assembled at each coarse degree with the fine level's element rotations
                      // (deform/degree_level_assembly.h), restricted to the constrained space
};

struct DeformableSolverSettings {
  double tolerance = 1e-3;  // relative residual of the implicit solve
  // The accuracy floor: the relative residual the frame plan guarantees this solve reaches
  // before fluids get time; in [tolerance, 1].
  double targetResidual = 1e-2;
  int maxIterations = 200;  // in [1, kMaxSolverIterations]
  static constexpr int kMaxSolverIterations = 100000;
  Preconditioner preconditioner = Preconditioner::Auto;
  PMultigridCoarseOperator pMultigridCoarseOperator = PMultigridCoarseOperator::Rediscretized;
};

// Contact of a deformable with itself (deform/pair_contacts.h). Auto: on for a mesh with more
// than one layer of elements (a corner node inside it); a single layer is a sheet or a thin
// shell, whose two sides are closer than a contact's reach.
enum class SelfCollision : int { Auto = 0, Off = 1, On = 2 };

struct DeformableDesc {
  std::string name;
  int degree = 1;
  TetMesh mesh;                            // rest shape, in the actor's local frame
  std::optional<SurfaceMesh> renderMesh;   // embedded in the tets; same frame as `mesh`
  Pose pose;                               // places the rest shape in the world
  Vec3 linearVelocity = Vec3::Zero();
  DeformableMaterial material;
  DeformableSolverSettings solver;
  int priority = 0;  // higher is served first when the frame budget is short (actor_priority.h)
  CollisionFilter filter;  // which colliders and deformables it contacts
  SelfCollision selfCollision = SelfCollision::Auto;
  void* userData = nullptr;
};

// The material's fields, for creation and run-time changes; messages name them as vpDeformableDef.
Status validateDeformableMaterial(const DeformableMaterial& material);

// Field names in messages follow vpDeformableDef. Repairs the mesh orientation and drops
// unused vertices (see validateAndRepairTetMesh). On failure `desc` is unchanged.
Status validateDeformableDesc(DeformableDesc& desc);

}  // namespace vp
