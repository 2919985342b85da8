// Thin solids in the cut-cell grid: the split-cell pass (cut_cell_components.h) disconnects the
// two sides of a plate one cell thick and leaves other colliders' fractions alone; sampling
// through open faces (grid_sampling.h) does not interpolate across a closed face.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "collide/face_coverage.h"
#include "core/task_system.h"
#include "fluid/advection/grid_sampling.h"
#include "fluid/pressure/cut_cell_poisson.h"
#include "fluid/solids/cut_cell_components.h"
#include "fluid/solids/face_fraction_field.h"

namespace vp {
namespace {

struct FractionScene {
  MacGridSpec grid;
  std::vector<PreparedCollider> colliders;
  FaceFractionField fractions;
};

void makeFractions(int n, const std::vector<ColliderShape>& shapes, FractionScene* scene) {
  scene->grid.h = 1.0 / n;
  scene->grid.nx = scene->grid.ny = scene->grid.nz = n;
  ASSERT_EQ(initFaceFractionField(scene->grid, &scene->fractions), Status::Ok);
  scene->colliders.assign(shapes.size(), PreparedCollider{});
  std::vector<const PreparedCollider*> list;
  for (size_t s = 0; s < shapes.size(); ++s) {
    ASSERT_EQ(prepareCollider(shapes[s], &scene->colliders[s]), Status::Ok) << lastError();
    list.push_back(&scene->colliders[s]);
  }
  ASSERT_EQ(computeFaceFractions(list.data(), static_cast<int>(list.size()), &scene->fractions), Status::Ok);
}

CutCellComponentStats closeSplitPieces(TaskSystem& tasks, FractionScene* scene) {
  std::vector<const PreparedCollider*> list;
  for (const PreparedCollider& c : scene->colliders) list.push_back(&c);
  CutCellComponentStats total;
  for (const PreparedCollider* c : list) {
    CutCellComponentStats s;
    EXPECT_EQ(closeSplitCellPieces(tasks, list.data(), static_cast<int>(list.size()), c->bounds, &scene->fractions, &s),
              Status::Ok);
    total.cutCells += s.cutCells;
    total.splitCells += s.splitCells;
    total.closedFaces += s.closedFaces;
  }
  return total;
}

// Cells reachable from `seed` through interior faces that the pressure operator treats as open
// (kMinOpenFraction: the exact coverage leaves round-off fractions inside solids).
std::vector<uint8_t> reachableCells(const FaceFractionField& f, int seedI, int seedJ, int seedK) {
  const MacGridSpec& g = f.grid;
  auto index = [&](int i, int j, int k) { return static_cast<size_t>(i) + static_cast<size_t>(g.nx) * (j + static_cast<size_t>(g.ny) * k); };
  std::vector<uint8_t> reached(static_cast<size_t>(g.nx) * g.ny * g.nz, 0);
  std::vector<Eigen::Vector3i> queue{Eigen::Vector3i(seedI, seedJ, seedK)};
  reached[index(seedI, seedJ, seedK)] = 1;
  const int cells[3] = {g.nx, g.ny, g.nz};
  for (size_t head = 0; head < queue.size(); ++head) {
    const Eigen::Vector3i c = queue[head];
    for (int a = 0; a < 3; ++a)
      for (int high = 0; high < 2; ++high) {
        Eigen::Vector3i nb = c, face = c;
        nb[a] += high ? 1 : -1;
        face[a] += high;
        if (nb[a] < 0 || nb[a] >= cells[a]) continue;
        if (!(f.open[a][f.faceIndex(a, face.x(), face.y(), face.z())] >= kMinOpenFraction)) continue;
        const size_t n = index(nb.x(), nb.y(), nb.z());
        if (reached[n]) continue;
        reached[n] = 1;
        queue.push_back(nb);
      }
  }
  return reached;
}

ColliderShape plateShape(const Eigen::Matrix3d& rotation, const Eigen::Vector3d& centre, double thickness) {
  ColliderShape plate;
  plate.kind = ShapeKind::Box;
  plate.halfExtents = Eigen::Vector3d(2.0, 0.5 * thickness, 2.0);
  plate.rotation = Eigen::Quaterniond(rotation);
  plate.translation = centre;
  return plate;
}

// A plate one cell thick, smaller than the grid, and a sphere whose cells its moves overlap.
ColliderShape movingPlate(double h) {
  ColliderShape plate = plateShape(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()).toRotationMatrix(),
                                   Eigen::Vector3d(0.45, 0.5, 0.5), h);
  plate.halfExtents = Eigen::Vector3d(0.2, 0.5 * h, 0.25);
  return plate;
}

ColliderShape sphereNearThePlate() {
  ColliderShape sphere;
  sphere.kind = ShapeKind::Sphere;
  sphere.radius = 0.15;
  sphere.translation = Eigen::Vector3d(0.62, 0.7, 0.5);
  return sphere;
}

// A plate one cell thick spanning the grid, at several angles and offsets: before the pass
// the open faces chain from below the plate to above it (through the cells it splits), after
// it no open face chain crosses, and the cells wholly on either side keep their faces.
TEST(FluidSplitCells, OneCellPlateSeparatesItsTwoSides) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const int n = 24;
  const double h = 1.0 / n;
  struct Case {
    double aboutZ, aboutX, offset;
  } cases[] = {{30, 0, 0}, {45, 0, 0.9}, {20, 0, 0.1}, {30, 25, 0}, {60, -15, 0.45}};
  for (const Case& c : cases) {
    const Eigen::Matrix3d rotation = (Eigen::AngleAxisd(c.aboutX * M_PI / 180, Eigen::Vector3d::UnitX()) *
                                      Eigen::AngleAxisd(c.aboutZ * M_PI / 180, Eigen::Vector3d::UnitZ()))
                                         .toRotationMatrix();
    const Eigen::Vector3d centre(0.5, 0.5 + c.offset * h, 0.5), normal = rotation * Eigen::Vector3d::UnitY();
    FractionScene scene;
    makeFractions(n, {plateShape(rotation, centre, h)}, &scene);
    const FaceFractionField before = scene.fractions;
    const CutCellComponentStats stats = closeSplitPieces(*tasks, &scene);
    const MacGridSpec& g = scene.grid;
    // Seed: the cell at the bottom of the grid's middle column, below the plate.
    const std::vector<uint8_t> reachedBefore = reachableCells(before, n / 2, 0, n / 2);
    const std::vector<uint8_t> reachedAfter = reachableCells(scene.fractions, n / 2, 0, n / 2);
    int aboveBefore = 0, aboveAfter = 0, belowAfter = 0, below = 0;
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          const size_t cell = static_cast<size_t>(i) + static_cast<size_t>(n) * (j + static_cast<size_t>(n) * k);
          const double side = (g.origin + h * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5) - centre).dot(normal);
          // Cells wholly above the plate: centre beyond half the thickness plus the cell's
          // half-extent along the normal.
          const double reach = 0.5 * h * normal.cwiseAbs().sum();
          if (side > 0.5 * h + reach) {
            aboveBefore += reachedBefore[cell];
            aboveAfter += reachedAfter[cell];
          }
          if (side < -0.5 * h - reach) {
            ++below;
            belowAfter += reachedAfter[cell];
          }
        }
    SCOPED_TRACE(testing::Message() << "plate " << c.aboutZ << " deg about z, " << c.aboutX << " about x, offset "
                                    << c.offset << " h");
    std::printf("plate %g/%g deg, offset %g h: %lld cut cells sampled, %lld split, %lld faces closed; cells above "
                "reached from below: %d before, %d after\n",
                c.aboutZ, c.aboutX, c.offset, static_cast<long long>(stats.cutCells),
                static_cast<long long>(stats.splitCells), static_cast<long long>(stats.closedFaces), aboveBefore,
                aboveAfter);
    EXPECT_GT(stats.splitCells, 0);
    EXPECT_GT(aboveBefore, 0);  // the leak path the pass removes
    EXPECT_EQ(aboveAfter, 0);
    EXPECT_EQ(belowAfter, below);  // the side itself stays connected
    // Running it again closes nothing more (the decisions depend on the colliders only).
    const FaceFractionField once = scene.fractions;
    closeSplitPieces(*tasks, &scene);
    for (int a = 0; a < 3; ++a) EXPECT_EQ(scene.fractions.open[a], once.open[a]);
  }
}

// A thin plate that moves: recomputing the fractions and the pass only around its old and new
// bounds (what the fluid actor does every step) gives exactly the full recompute at the new
// pose, with a sphere nearby whose cells the moved region overlaps.
TEST(FluidSplitCells, IncrementalUpdateOfAMovingPlateMatchesAFullRecompute) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const int n = 24;
  const double h = 1.0 / n;
  ColliderShape plate = movingPlate(h);
  const ColliderShape sphere = sphereNearThePlate();
  FractionScene moving;
  makeFractions(n, {plate, sphere}, &moving);
  closeSplitPieces(*tasks, &moving);
  std::vector<const PreparedCollider*> list{&moving.colliders[0], &moving.colliders[1]};
  for (int step = 0; step < 4; ++step) {
    const Aabb oldBounds = moving.colliders[0].bounds;
    plate.translation += Eigen::Vector3d(0.37 * h, 0.21 * h, -0.13 * h);
    plate.rotation = Eigen::AngleAxisd(0.05, Eigen::Vector3d::UnitX()) * plate.rotation;
    ASSERT_EQ(setColliderPose(&moving.colliders[0], plate.rotation, plate.translation), Status::Ok);
    const Aabb newBounds = moving.colliders[0].bounds;
    ASSERT_EQ(updateFaceFractions(list.data(), 2, oldBounds, newBounds, &moving.fractions), Status::Ok);
    CutCellComponentStats oldStats, newStats;
    ASSERT_EQ(closeSplitCellPieces(*tasks, list.data(), 2, oldBounds, &moving.fractions, &oldStats), Status::Ok);
    ASSERT_EQ(closeSplitCellPieces(*tasks, list.data(), 2, newBounds, &moving.fractions, &newStats), Status::Ok);
    EXPECT_GT(oldStats.closedFaces + newStats.closedFaces, 0);
    FractionScene fresh;
    makeFractions(n, {plate, sphere}, &fresh);
    closeSplitPieces(*tasks, &fresh);
    for (int a = 0; a < 3; ++a) EXPECT_EQ(moving.fractions.open[a], fresh.fractions.open[a]) << "step " << step;
  }
}

// The same update as passes run in slices (what a fluid step spread over frames does): any
// slice size gives bitwise the fractions of the whole calls, full recompute and moving plate.
TEST(FluidSplitCells, FractionPassesInSlicesMatchTheWholeCalls) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  const int n = 24;
  const double h = 1.0 / n;
  ColliderShape plate = movingPlate(h);
  plate.angularVelocity = Eigen::Vector3d(0.0, 1.5, 0.0);
  const ColliderShape sphere = sphereNearThePlate();
  FractionScene whole;
  makeFractions(n, {plate, sphere}, &whole);
  closeSplitPieces(*tasks, &whole);
  std::vector<const PreparedCollider*> list{&whole.colliders[0], &whole.colliders[1]};
  for (int64_t sliceSamples : {int64_t(1), int64_t(997), int64_t(1) << 14}) {
    FaceFractionField sliced;
    ASSERT_EQ(initFaceFractionField(whole.grid, &sliced), Status::Ok);
    SlabPasses passes(*tasks);
    ASSERT_EQ(addFaceFractionPasses(passes, list.data(), 2, &sliced), Status::Ok);
    for (const PreparedCollider* c : list)
      ASSERT_EQ(addSplitCellPasses(passes, list.data(), 2, c->bounds, &sliced, nullptr), Status::Ok);
    int slices = 1;
    while (!passes.runSlice(sliceSamples)) ++slices;
    EXPECT_GT(slices, sliceSamples > 1000 ? 2 : 100);
    for (int a = 0; a < 3; ++a) {
      ASSERT_EQ(sliced.open[a], whole.fractions.open[a]) << "full, axis " << a << ", slices of " << sliceSamples;
      ASSERT_EQ(sliced.solidVelocity[a], whole.fractions.solidVelocity[a]) << "axis " << a;
    }
  }
  FaceFractionField moving = whole.fractions;
  for (int step = 0; step < 3; ++step) {
    const Aabb oldBounds = whole.colliders[0].bounds;
    plate.rotation = Eigen::AngleAxisd(0.1, Eigen::Vector3d::UnitY()) * plate.rotation;
    ASSERT_EQ(setColliderPose(&whole.colliders[0], plate.rotation, plate.translation), Status::Ok);
    const Aabb newBounds = whole.colliders[0].bounds;
    ASSERT_EQ(updateFaceFractions(list.data(), 2, oldBounds, newBounds, &whole.fractions), Status::Ok);
    ASSERT_EQ(closeSplitCellPieces(*tasks, list.data(), 2, oldBounds, &whole.fractions, nullptr), Status::Ok);
    ASSERT_EQ(closeSplitCellPieces(*tasks, list.data(), 2, newBounds, &whole.fractions, nullptr), Status::Ok);
    SlabPasses passes(*tasks);
    ASSERT_EQ(addFaceFractionUpdatePasses(passes, list.data(), 2, oldBounds, newBounds, &moving), Status::Ok);
    CutCellComponentStats stats;
    ASSERT_EQ(addSplitCellPasses(passes, list.data(), 2, oldBounds, &moving, nullptr), Status::Ok);
    ASSERT_EQ(addSplitCellPasses(passes, list.data(), 2, newBounds, &moving, &stats), Status::Ok);
    while (!passes.runSlice(333)) {
    }
    EXPECT_GT(stats.cutCells, 0);
    for (int a = 0; a < 3; ++a) {
      ASSERT_EQ(moving.open[a], whole.fractions.open[a]) << "step " << step << ", axis " << a;
      ASSERT_EQ(moving.solidVelocity[a], whole.fractions.solidVelocity[a]) << "step " << step << ", axis " << a;
    }
  }
}

// Colliders thicker than two cells split no cell the pass looks at: their fractions stay
// exactly the computed ones (so every test of the exact fractions still holds in the actor).
TEST(FluidSplitCells, ThickCollidersKeepTheirExactFractions) {
  auto tasks = TaskSystem::create(TaskHooks{}, 2);
  ColliderShape sphere;
  sphere.kind = ShapeKind::Sphere;
  sphere.radius = 0.2;
  sphere.translation = Eigen::Vector3d(0.5, 0.55, 0.5);
  ColliderShape box;
  box.kind = ShapeKind::Box;
  box.halfExtents = Eigen::Vector3d(0.15, 0.06, 0.2);
  box.rotation = Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()) * Eigen::AngleAxisd(-0.3, Eigen::Vector3d::UnitX());
  box.translation = Eigen::Vector3d(0.3, 0.25, 0.5);
  ColliderShape capsule;
  capsule.kind = ShapeKind::Capsule;
  capsule.radius = 0.1;
  capsule.halfHeight = 0.2;
  capsule.rotation = box.rotation;
  capsule.translation = Eigen::Vector3d(0.62, 0.5, 0.45);
  for (int n : {24, 48}) {
    for (const ColliderShape& shape : {sphere, box, capsule}) {
      FractionScene scene;
      makeFractions(n, {shape}, &scene);
      const FaceFractionField before = scene.fractions;
      const CutCellComponentStats stats = closeSplitPieces(*tasks, &scene);
      EXPECT_EQ(stats.closedFaces, 0) << shapeKindName(shape.kind) << " n " << n;
      for (int a = 0; a < 3; ++a) EXPECT_EQ(scene.fractions.open[a], before.open[a]);
    }
  }
}

// A small sphere (thinner than two cells) is sampled; a sphere never separates anything, and
// the cells it cuts are in one piece each unless it leaves corners: whatever it closes, the
// fluid around it stays one connected region.
TEST(FluidSplitCells, SmallSphereLeavesTheFluidConnected) {
  auto tasks = TaskSystem::create(TaskHooks{}, 1);
  const int n = 12;
  for (double radius : {0.6, 0.8, 1.2}) {
    ColliderShape sphere;
    sphere.kind = ShapeKind::Sphere;
    sphere.radius = radius / n;
    sphere.translation = Eigen::Vector3d(0.5 + 0.13 / n, 0.5, 0.5 - 0.21 / n);
    FractionScene scene;
    makeFractions(n, {sphere}, &scene);
    closeSplitPieces(*tasks, &scene);
    const std::vector<uint8_t> reached = reachableCells(scene.fractions, 0, 0, 0);
    int fluid = 0, connected = 0;
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < n; ++j)
        for (int i = 0; i < n; ++i) {
          bool open = false;
          for (int a = 0; a < 3; ++a)
            for (int high = 0; high < 2; ++high) {
              Eigen::Vector3i face(i, j, k);
              face[a] += high;
              open = open || scene.fractions.open[a][scene.fractions.faceIndex(a, face.x(), face.y(), face.z())] >=
                                 kMinOpenFraction;
            }
          fluid += open;
          connected += open && reached[static_cast<size_t>(i) + static_cast<size_t>(n) * (j + static_cast<size_t>(n) * k)];
        }
    EXPECT_EQ(connected, fluid) << "radius " << radius << " h";
  }
}

// Open-face sampling: equal to trilinear sampling where the block's inner faces are open, and
// blind to the cells behind a closed face.
TEST(FluidSplitCells, ConnectedSamplingDoesNotInterpolateAcrossClosedFaces) {
  const Eigen::Vector3i dims(3, 3, 2);
  const int cells = dims.prod();
  std::vector<double> values(static_cast<size_t>(cells));
  for (int c = 0; c < cells; ++c) values[static_cast<size_t>(c)] = 1.0 + 0.37 * c + 0.05 * c * c;
  auto cell = [&](int i, int j, int k) { return static_cast<size_t>(i + dims.x() * (j + dims.y() * k)); };
  // All faces open: blockOpen everywhere a block starts.
  std::vector<uint8_t> faces(static_cast<size_t>(cells), 0x3F | kCellIsFluid), blockOpen(static_cast<size_t>(cells), 0);
  for (int k = 0; k + 1 < dims.z(); ++k)
    for (int j = 0; j + 1 < dims.y(); ++j)
      for (int i = 0; i + 1 < dims.x(); ++i) blockOpen[cell(i, j, k)] = 1;
  const Eigen::Vector3d points[] = {{0.3, 0.6, 0.2}, {1.7, 0.1, 0.9}, {1.2, 1.8, 0.5}, {0.0, 0.0, 0.0}};
  for (const Eigen::Vector3d& p : points) {
    SampleRange plain, connected;
    EXPECT_EQ(connectedTrilinearSample(values.data(), dims, p, faces.data(), blockOpen.data(), &connected),
              trilinearSample(values.data(), dims, p, &plain));
    EXPECT_EQ(connected.lo, plain.lo);
    EXPECT_EQ(connected.hi, plain.hi);
  }
  // Same faces, but the blocks not flagged open: the flood fill reaches every corner, so the
  // result is trilinear interpolation again (up to round-off of the renormalization).
  std::fill(blockOpen.begin(), blockOpen.end(), 0);
  for (const Eigen::Vector3d& p : points)
    EXPECT_NEAR(connectedTrilinearSample(values.data(), dims, p, faces.data(), blockOpen.data()),
                trilinearSample(values.data(), dims, p), 1e-12);
  // A wall between x = 0 and x = 1 (cells i = 0 closed on their high x face, i = 1 on their
  // low one): a point nearer the i = 0 cells uses only them, whatever the i = 1 values are.
  for (int k = 0; k < dims.z(); ++k)
    for (int j = 0; j < dims.y(); ++j) {
      faces[cell(0, j, k)] &= static_cast<uint8_t>(~(1u << 1));
      faces[cell(1, j, k)] &= static_cast<uint8_t>(~(1u << 0));
    }
  const Eigen::Vector3d p(0.4, 0.5, 0.25);
  SampleRange range;
  const double v = connectedTrilinearSample(values.data(), dims, p, faces.data(), blockOpen.data(), &range);
  std::vector<double> onlyLeft = values;
  for (int k = 0; k < dims.z(); ++k)
    for (int j = 0; j < dims.y(); ++j) onlyLeft[cell(1, j, k)] = 1e6;  // would show if used
  EXPECT_EQ(connectedTrilinearSample(onlyLeft.data(), dims, p, faces.data(), blockOpen.data()), v);
  // The i = 0 column interpolated in y and z alone.
  const double wy = 0.5, wz = 0.25;
  const double expected = (1 - wy) * (1 - wz) * values[cell(0, 0, 0)] + wy * (1 - wz) * values[cell(0, 1, 0)] +
                          (1 - wy) * wz * values[cell(0, 0, 1)] + wy * wz * values[cell(0, 1, 1)];
  EXPECT_NEAR(v, expected, 1e-12);
  EXPECT_GE(range.lo, std::min({values[cell(0, 0, 0)], values[cell(0, 1, 0)], values[cell(0, 0, 1)], values[cell(0, 1, 1)]}));
  EXPECT_LE(range.hi, std::max({values[cell(0, 0, 0)], values[cell(0, 1, 0)], values[cell(0, 0, 1)], values[cell(0, 1, 1)]}));
  // A cell with no open face (its neighbours' faces towards it closed too) is never used,
  // even where it is the nearest sample.
  faces[cell(0, 0, 0)] = 0;
  faces[cell(0, 1, 0)] &= static_cast<uint8_t>(~(1u << 2));
  faces[cell(0, 0, 1)] &= static_cast<uint8_t>(~(1u << 4));
  const Eigen::Vector3d q(0.2, 0.3, 0.4);
  const double w010 = 0.8 * 0.3 * 0.6, w001 = 0.8 * 0.7 * 0.4, w011 = 0.8 * 0.3 * 0.4;
  EXPECT_NEAR(connectedTrilinearSample(values.data(), dims, q, faces.data(), blockOpen.data()),
              (w010 * values[cell(0, 1, 0)] + w001 * values[cell(0, 0, 1)] + w011 * values[cell(0, 1, 1)]) /
                  (w010 + w001 + w011),
              1e-12);
}

}  // namespace
}  // namespace vp
