// The cantilever beam of BM_DeformLinearBeam, run in Bullet 3.24's own deformable solver
// (btDeformableMultiBodyDynamicsWorld, implicit backward Euler, btDeformableLinearElasticityForce)
// so the two solvers are measured on the same mesh in the same benchmark run.
//
// Bullet's deformable solver is single-threaded (nothing in BulletSoftBody runs in parallel), so
// `hz` here is 1 thread; VolPhys' BM_DeformLinearBeam reports `hz` with 2 threads.
#include <benchmark/benchmark.h>

#include <BulletSoftBody/btDeformableBodySolver.h>
#include <BulletSoftBody/btDeformableGravityForce.h>
#include <BulletSoftBody/btDeformableLinearElasticityForce.h>
#include <BulletSoftBody/btDeformableMultiBodyConstraintSolver.h>
#include <BulletSoftBody/btDeformableMultiBodyDynamicsWorld.h>
#include <BulletSoftBody/btSoftBody.h>
#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <btBulletDynamicsCommon.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <string>
#include <vector>

#include "beam_mesh.h"

namespace vp::bench {
namespace {

// The beam: 4 m x 1 m x 1 m of a stiff-rubber-like solid, clamped at x = 0, under its own weight.
constexpr double kLength = 4.0;  // along X
constexpr double kHeight = 1.0;  // along Y (up, the bending direction)
constexpr double kWidth = 1.0;   // along Z
constexpr double kYoungModulus = 1e8;
constexpr double kPoissonRatio = 0.3;
constexpr double kDensity = 1000.0;
constexpr double kGravity = 9.81;
constexpr double kTimeStep = 1.0 / 60.0;
constexpr int kStepCount = 60;

// Bullet's own defaults for btDeformableLinearElasticityForce's Rayleigh damping (mass-proportional
// alpha, stiffness-proportional beta). Spelled out so a reader sees the beam is damped: with
// beta = 0.01 s the first bending mode (about 3.2 Hz) has a damping ratio near 0.1.
constexpr double kDampingAlpha = 0.01;
constexpr double kDampingBeta = 0.01;

// Stepping stops once it has run this long and `hz` is extrapolated from the steps that ran
// (counter steps_measured < 60); tip_dy is then left out because it is not the step-60 value.
// The 98304-tet beam takes several minutes for 60 steps in Bullet on a 2-core machine, which is
// too long for a routine benchmark run; VP_BULLET_BEAM_MAX_SECONDS=1000 lets it finish.
double maxSteppingSeconds() {
  constexpr double kDefaultSeconds = 120.0;
  const char* text = std::getenv("VP_BULLET_BEAM_MAX_SECONDS");
  if (text == nullptr) return kDefaultSeconds;
  const double seconds = std::strtod(text, nullptr);
  return seconds > 0 ? seconds : kDefaultSeconds;
}

// CPU time of the calling thread: on a shared machine wall time also counts other people's work,
// and Bullet's stepping runs on this one thread only.
double threadCpuSeconds() {
  timespec now{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &now);
  return double(now.tv_sec) + 1e-9 * double(now.tv_nsec);
}

// Euler–Bernoulli static tip deflection under self-weight, qL^4 / (8 E I): the dynamic beam
// oscillates around (a bit more than) this at t = 1 s. Shear (Timoshenko) adds ~6% for L/h = 4,
// and linear tets are stiffer than the continuum, so expect the same order, not equality.
double eulerBernoulliSelfWeightTipDeflection() {
  const double lineLoad = kDensity * kGravity * kWidth * kHeight;
  const double secondMoment = kWidth * kHeight * kHeight * kHeight / 12.0;
  return lineLoad * kLength * kLength * kLength * kLength / (8.0 * kYoungModulus * secondMoment);
}

// Owns every Bullet object of one beam simulation and tears them down in the order Bullet needs:
// the body leaves the world before the world, the world goes before its solvers, forces last
// (the world and solver keep raw pointers to them and never delete them).
class BulletBeamWorld {
 public:
  explicit BulletBeamWorld(const BeamMesh& mesh) {
    collisionConfig_ = std::make_unique<btSoftBodyRigidBodyCollisionConfiguration>();
    dispatcher_ = std::make_unique<btCollisionDispatcher>(collisionConfig_.get());
    broadphase_ = std::make_unique<btDbvtBroadphase>();
    deformableSolver_ = std::make_unique<btDeformableBodySolver>();
    constraintSolver_ = std::make_unique<btDeformableMultiBodyConstraintSolver>();
    constraintSolver_->setDeformableSolver(deformableSolver_.get());
    world_ = std::make_unique<btDeformableMultiBodyDynamicsWorld>(
        dispatcher_.get(), broadphase_.get(), constraintSolver_.get(), collisionConfig_.get(), deformableSolver_.get());

    const btVector3 gravity(0, btScalar(-kGravity), 0);
    world_->setGravity(gravity);
    world_->getWorldInfo().m_gravity = gravity;
    // Implicit (backward Euler) elasticity. The world and the body solver each keep their own
    // "implicit" and "projection" flags in 3.24 (the world's setters do not forward), so both
    // are set. Projection must be on: in 3.24 the default implicit path (conjugate residual on
    // the Lagrange-multiplier system) returns a zero velocity change when nothing is in contact,
    // so the beam never moves, not even in free fall; with projection the momentum solve is
    // Bullet's preconditioned CG (Baraff-Witkin projection, at most 300 iterations), which falls
    // exactly as g t^2 / 2 with gravity alone and bends the beam as expected. No line search and
    // Bullet's default of one Newton iteration per step.
    world_->setImplicit(true);
    deformableSolver_->setImplicit(true);
    world_->setUseProjection(true);
    deformableSolver_->m_useProjection = true;
    world_->setLineSearch(false);
    deformableSolver_->setLineSearch(false);

    beam_ = makeSoftBody(mesh);
    world_->addSoftBody(beam_.get());

    const double shearModulus = kYoungModulus / (2.0 * (1.0 + kPoissonRatio));
    const double lameLambda = kYoungModulus * kPoissonRatio / ((1.0 + kPoissonRatio) * (1.0 - 2.0 * kPoissonRatio));
    elasticity_ = std::make_unique<btDeformableLinearElasticityForce>(btScalar(shearModulus), btScalar(lameLambda),
                                                                      btScalar(kDampingAlpha), btScalar(kDampingBeta));
    gravityForce_ = std::make_unique<btDeformableGravityForce>(gravity);
    world_->addForce(beam_.get(), elasticity_.get());
    world_->addForce(beam_.get(), gravityForce_.get());
  }

  ~BulletBeamWorld() {
    world_->removeSoftBody(beam_.get());
    world_.reset();
    beam_.reset();
    constraintSolver_.reset();
    deformableSolver_.reset();
    broadphase_.reset();
    dispatcher_.reset();
    collisionConfig_.reset();
    elasticity_.reset();
    gravityForce_.reset();
  }

  BulletBeamWorld(const BulletBeamWorld&) = delete;
  BulletBeamWorld& operator=(const BulletBeamWorld&) = delete;

  // One step of exactly kTimeStep: maxSubSteps = 0 makes stepSimulation take the given dt as a
  // single internal step (no fixed-step accumulator, no interpolation). Returns the number of
  // internal steps Bullet ran, which must be 1.
  int step() { return world_->stepSimulation(btScalar(kTimeStep), 0); }

  btSoftBody& beam() { return *beam_; }

  // Bullet's element measure is det(Dm) / 6, signed: positive for every tet means Bullet reads
  // the mesh's orientation the way the mesh generator wrote it.
  bool allElementMeasuresPositive() const {
    for (int t = 0; t < beam_->m_tetras.size(); ++t)
      if (!(beam_->m_tetras[t].m_element_measure > 0)) return false;
    return true;
  }

 private:
  std::unique_ptr<btSoftBody> makeSoftBody(const BeamMesh& mesh) {
    // Lumped mass: each tet gives a quarter of rho * volume to each of its corners. Clamped
    // vertices get mass 0, which Bullet treats as infinite mass (inverse mass 0, velocity held 0).
    const int32_t vertexCount = mesh.vertexCount();
    std::vector<btScalar> masses(size_t(vertexCount), 0);
    std::vector<double> lumpedMass(size_t(vertexCount), 0.0);
    for (int32_t t = 0; t < mesh.tetCount(); ++t) {
      const double quarterMass = 0.25 * kDensity * signedTetVolume(mesh, t);
      for (int c = 0; c < 4; ++c) lumpedMass[size_t(mesh.tets[size_t(4) * t + c])] += quarterMass;
    }
    for (int32_t v = 0; v < vertexCount; ++v) masses[size_t(v)] = btScalar(lumpedMass[size_t(v)]);
    for (int32_t v : mesh.fixedVertices) masses[size_t(v)] = 0;

    std::vector<btVector3> positions(static_cast<size_t>(vertexCount));
    for (int32_t v = 0; v < vertexCount; ++v)
      positions[size_t(v)] = btVector3(btScalar(mesh.vertices[size_t(3) * v]), btScalar(mesh.vertices[size_t(3) * v + 1]),
                                       btScalar(mesh.vertices[size_t(3) * v + 2]));

    auto body = std::make_unique<btSoftBody>(&world_->getWorldInfo(), vertexCount, positions.data(), masses.data());
    for (int32_t t = 0; t < mesh.tetCount(); ++t) {
      const int32_t* corners = &mesh.tets[size_t(4) * t];
      body->appendTetra(corners[0], corners[1], corners[2], corners[3]);
    }
    // No links: btDeformableLinearElasticityForce works on tets only (links feed mass-spring
    // forces). Boundary faces as Bullet's own tet loaders make them, so the per-step face work
    // (normals, face tree refit) is what a real Bullet deformable pays.
    btSoftBodyHelpers::generateBoundaryFaces(body.get());
    // The rest shape inverse (Dm^-1) and per-tet scratch that the elasticity force reads.
    body->initializeDmInverse();
    // Filled with the rest state (F = I): Bullet's own default fill copies uninitialized
    // matrices, which the first step overwrites but the compiler rightly warns about.
    btSoftBody::TetraScratch restScratch;
    restScratch.m_F = btMatrix3x3::getIdentity();
    restScratch.m_trace = 3;
    restScratch.m_J = 1;
    restScratch.m_cofF = btMatrix3x3::getIdentity();
    restScratch.m_corotation = btMatrix3x3::getIdentity();
    body->m_tetraScratches.resize(body->m_tetras.size(), restScratch);
    body->m_tetraScratchesTn.resize(body->m_tetras.size(), restScratch);

    // No ground and no other bodies: switch off every collision kind, self-collision included.
    body->m_cfg.collisions = 0;
    body->setSelfCollision(false);
    // The beam must not fall asleep when it slows near its rest shape: that would freeze it.
    body->setActivationState(DISABLE_DEACTIVATION);
    return body;
  }

  std::unique_ptr<btSoftBodyRigidBodyCollisionConfiguration> collisionConfig_;
  std::unique_ptr<btCollisionDispatcher> dispatcher_;
  std::unique_ptr<btDbvtBroadphase> broadphase_;
  std::unique_ptr<btDeformableBodySolver> deformableSolver_;
  std::unique_ptr<btDeformableMultiBodyConstraintSolver> constraintSolver_;
  std::unique_ptr<btDeformableMultiBodyDynamicsWorld> world_;
  std::unique_ptr<btSoftBody> beam_;
  std::unique_ptr<btDeformableLinearElasticityForce> elasticity_;
  std::unique_ptr<btDeformableGravityForce> gravityForce_;
};

// Arg: the tet count (12288 -> 32x8x8 cubes, 98304 -> 64x16x16). Each iteration builds a fresh
// world (not timed) and times only the 60 steps (manual time).
void BM_BulletDeformBeam(benchmark::State& state) {
  BeamCells cells;
  if (!beamCellsForTetCount(state.range(0), &cells)) {
    state.SkipWithError("the argument is not a tet count 24 n^3 of a 4n x n x n beam");
    return;
  }
  const BeamMesh mesh = makeBeamMesh(cells.x, cells.y, cells.z, kLength, kHeight, kWidth);
  const std::string defect = findBeamMeshDefect(mesh, kLength * kHeight * kWidth);
  if (!defect.empty()) {
    state.SkipWithError(defect.c_str());
    return;
  }

  const double maxSeconds = maxSteppingSeconds();
  double steppingSeconds = 0;
  double steppingCpuSeconds = 0;
  int stepsRun = 0;
  double tipDisplacementY = 0;
  for (auto _ : state) {
    BulletBeamWorld world(mesh);
    if (!world.allElementMeasuresPositive()) {
      state.SkipWithError("Bullet computed a non-positive tet volume: orientation mismatch");
      return;
    }
    const btSoftBody::Node& tip = world.beam().m_nodes[mesh.tipVertex];
    const btScalar tipRestY = tip.m_x.getY();

    stepsRun = 0;
    const double cpuStart = threadCpuSeconds();
    const auto start = std::chrono::steady_clock::now();
    double elapsed = 0;
    while (stepsRun < kStepCount && elapsed < maxSeconds) {
      if (world.step() != 1) {
        state.SkipWithError("Bullet did not run exactly one internal step per stepSimulation call");
        return;
      }
      ++stepsRun;
      elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    }
    state.SetIterationTime(elapsed);
    steppingSeconds += elapsed;
    steppingCpuSeconds += threadCpuSeconds() - cpuStart;
    tipDisplacementY = double(tip.m_x.getY() - tipRestY);
  }

  const double stepsTimed = double(stepsRun) * double(state.iterations());
  state.counters["hz"] = benchmark::Counter(stepsTimed / steppingSeconds);
  state.counters["hz_cpu"] = benchmark::Counter(stepsTimed / steppingCpuSeconds);
  state.counters["steps_measured"] = benchmark::Counter(double(stepsRun));
  // tip_dy is the step-60 value only; a run cut short by maxSteppingSeconds() leaves it out.
  if (stepsRun == kStepCount) state.counters["tip_dy"] = benchmark::Counter(tipDisplacementY);

  char label[160];
  std::snprintf(label, sizeof label, "%dx%dx%d cubes, %d verts, 1 thread, Euler-Bernoulli static tip_dy %.4f m",
                cells.x, cells.y, cells.z, mesh.vertexCount(), -eulerBernoulliSelfWeightTipDeflection());
  state.SetLabel(label);
}
BENCHMARK(BM_BulletDeformBeam)->Arg(12288)->Arg(98304)->Unit(benchmark::kMillisecond)->Iterations(1)->UseManualTime();

}  // namespace
}  // namespace vp::bench
