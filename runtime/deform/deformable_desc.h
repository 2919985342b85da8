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

// Auto takes p-multigrid for degree >= 2: fewer CG iterations and less time than aggregation
// multigrid on the same matrix (BM_DeformSolve/{pmg_pcg,amg_pcg}/cubic,
// BM_DeformQuadraticBeam{,AggregationMultigrid}/13000; figures in docs/choices.md, p-multigrid).
enum class Preconditioner : int {
  Auto = 0,         // above kMultigridMinNodes nodes p-multigrid for degree >= 2, aggregation
                    // multigrid for degree 1; block-Jacobi below, but aggregation multigrid for
                    // a linear mesh's long steps (kMultigridWaveCrossings)
  BlockJacobi = 1,
  Multigrid = 2,    // aggregation multigrid with rigid-body modes (linalg/aggregation_multigrid.h)
  PMultigrid = 3,   // V-cycle over the degrees, aggregation multigrid on the linear level
                    // (linalg/p_multigrid.h); degree 1 has no lower degree and gets Multigrid
};

// Below this many nodes the multigrid's setup costs more than the CG iterations it saves. A
// body in contact pays the setup again after every contact pass that changes its constraints,
// so the bound comes from a jelly in contact, not a contact-free beam (docs/choices.md,
// Preconditioner).
constexpr int kMultigridMinNodes = 1000;
// Below kMultigridMinNodes, Auto still takes the multigrid for a step over which an elastic
// pressure wave crosses more than this many node spacings: block-Jacobi's CG iterations grow
// with that count, the multigrid's stay flat (docs/choices.md, Preconditioner).
constexpr double kMultigridWaveCrossings = 10.0;

// How p-multigrid gets its coarse operators. Re-discretized is the default: a few more CG
// iterations than Galerkin for a much cheaper setup (linalg/p_multigrid.h; docs/choices.md).
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
