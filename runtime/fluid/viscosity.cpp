// Implicit cut-cell viscosity (see viscosity.h).
#include "fluid/viscosity.h"

#include <algorithm>
#include <cmath>

#include "core/parallel_for.h"
#include "fluid/pressure/cut_cell_poisson.h"
#include "fluid/surface/free_surface.h"

namespace vp {
namespace {

constexpr int64_t kUnknownGrain = 2048;

int cellsAlong(const MacGridSpec& g, int axis) { return axis == 0 ? g.nx : axis == 1 ? g.ny : g.nz; }

// A face carries fluid when one of its cells inside the domain is fluid (every cell for smoke).
bool touchesFluid(const MacGrid& grid, const double* liquidPhi, int axis, const Eigen::Vector3i& f) {
  if (liquidPhi == nullptr) return true;
  Eigen::Vector3i low = f;
  low[axis] -= 1;
  if (f[axis] > 0 && isLiquid(liquidPhi[grid.cellIndex(low.x(), low.y(), low.z())])) return true;
  return f[axis] < cellsAlong(grid.spec, axis) && isLiquid(liquidPhi[grid.cellIndex(f.x(), f.y(), f.z())]);
}

bool isUnknown(const MacGrid& grid, const FaceFractionField& fractions, const double* liquidPhi, int axis,
               const Eigen::Vector3i& f) {
  return effectiveOpenFraction(grid, fractions, axis, f.x(), f.y(), f.z()) > 0.0 &&
         touchesFluid(grid, liquidPhi, axis, f);
}

Eigen::Vector3i faceCoords(const Eigen::Vector3i& dims, int64_t face) {
  const int64_t row = face / dims.x();
  return Eigen::Vector3i(static_cast<int>(face % dims.x()), static_cast<int>(row % dims.y()),
                         static_cast<int>(row / dims.y()));
}

// Numbers the unknowns axis by axis, face order within an axis, so the numbering (and so the
// CG's reductions) does not depend on the worker count: rows of faces are counted in
// parallel, offset serially, then filled in parallel.
void numberUnknowns(TaskSystem& tasks, const MacGrid& grid, const FaceFractionField& fractions,
                    const double* liquidPhi, ViscosityWorkspace& w) {
  w.face.clear();
  int64_t total = 0;
  for (int a = 0; a < 3; ++a) {
    w.axisBegin[a] = total;
    const Eigen::Vector3i d = grid.faceDims(a);
    const int64_t rows = static_cast<int64_t>(d.y()) * d.z();
    Array<int32_t>& unknownOf = w.unknownOfFace[a];
    unknownOf.resize(static_cast<size_t>(rows) * d.x());
    w.rowStart.assign(static_cast<size_t>(rows) + 1, 0);
    parallelFor(tasks, rows, 16, [&](int64_t begin, int64_t end) {
      for (int64_t row = begin; row < end; ++row) {
        const int j = static_cast<int>(row % d.y()), k = static_cast<int>(row / d.y());
        int64_t count = 0;
        for (int i = 0; i < d.x(); ++i) {
          const bool unknown = isUnknown(grid, fractions, liquidPhi, a, Eigen::Vector3i(i, j, k));
          unknownOf[static_cast<size_t>(row * d.x() + i)] = unknown ? 0 : -1;
          count += unknown;
        }
        w.rowStart[static_cast<size_t>(row) + 1] = count;
      }
    });
    w.rowStart[0] = total;
    for (int64_t row = 0; row < rows; ++row) w.rowStart[static_cast<size_t>(row) + 1] += w.rowStart[static_cast<size_t>(row)];
    total = w.rowStart[static_cast<size_t>(rows)];
    w.face.resize(static_cast<size_t>(total));
    parallelFor(tasks, rows, 16, [&](int64_t begin, int64_t end) {
      for (int64_t row = begin; row < end; ++row) {
        int64_t next = w.rowStart[static_cast<size_t>(row)];
        for (int64_t f = row * d.x(); f < (row + 1) * d.x(); ++f) {
          if (unknownOf[static_cast<size_t>(f)] < 0) continue;
          unknownOf[static_cast<size_t>(f)] = static_cast<int32_t>(next);
          w.face[static_cast<size_t>(next++)] = f;
        }
      }
    });
  }
  w.axisBegin[3] = total;
}

int axisOf(const ViscosityWorkspace& w, int64_t unknown) {
  return unknown < w.axisBegin[1] ? 0 : unknown < w.axisBegin[2] ? 1 : 2;
}

// visit(neighbourUnknown, weight) for the unknowns coupled to `unknown`, and returns through
// `diagonal` and `dirichlet` the sums of the stencil weights and of weight * boundary value
// (viscosity.h gives the table), in units of 1 / h^2; `solidWeight`, where set, the part of
// the weights that couples to solids.
template <class Visit>
void stencil(const MacGrid& grid, const FaceFractionField& fractions, const double* liquidPhi,
             const ViscosityWorkspace& w, int64_t unknown, double* diagonal, double* dirichlet, const Visit& visit,
             double* solidWeight = nullptr) {
  const int a = axisOf(w, unknown);
  const Eigen::Vector3i dims = grid.faceDims(a);
  const int64_t face = w.face[static_cast<size_t>(unknown)];
  const Eigen::Vector3i f = faceCoords(dims, face);
  const double openHere = w.open[static_cast<size_t>(unknown)];
  const Array<double>& solid = fractions.solidVelocity[a];
  double diag = 0.0, boundary = 0.0, toSolids = 0.0;
  for (int b = 0; b < 3; ++b)
    for (int high = 0; high < 2; ++high) {
      Eigen::Vector3i n = f;
      n[b] += high ? 1 : -1;
      if (n[b] < 0 || n[b] >= dims[b]) {
        // Past the domain: along the face's own axis f is on an Open side (a Wall-side face
        // is no unknown), so the flow continues; across it the side decides.
        if (b != a && grid.side(b, high != 0) == DomainSide::Wall) diag += 2.0;
        continue;
      }
      const size_t nb = grid.faceIndex(a, n.x(), n.y(), n.z());
      if (grid.isWallFace(a, n.x(), n.y(), n.z())) {
        diag += 1.0;
        continue;
      }
      const int32_t other = w.unknownOfFace[a][nb];
      if (other >= 0) {
        const double openThere = w.open[static_cast<size_t>(other)];
        const double coupling = std::min(openHere, openThere);
        diag += 1.0;
        boundary += (1.0 - coupling) * solid[openHere < openThere ? static_cast<size_t>(face) : nb];
        toSolids += 1.0 - coupling;
        visit(other, coupling);
      } else if (touchesFluid(grid, liquidPhi, a, n)) {
        // Closed by a solid next to the fluid.
        diag += 1.0;
        boundary += solid[nb];
        toSolids += 1.0;
      }
    }
  *diagonal = diag;
  *dirichlet = boundary;
  if (solidWeight != nullptr) *solidWeight = toSolids;
}

}  // namespace

Status applyViscosity(TaskSystem& tasks, MacGrid& grid, const FaceFractionField& fractions,
                      const double* liquidPhi, double kinematicViscosity, double dt, const Deadline& deadline,
                      const ViscositySettings& settings, ViscosityWorkspace& w, ViscosityStats* stats) {
  if (stats != nullptr) *stats = ViscosityStats{};
  if (!(kinematicViscosity >= 0.0) || !std::isfinite(kinematicViscosity))
    return fail(Status::InvalidArgument, "viscosity: kinematicViscosity = %g must be finite and >= 0",
                kinematicViscosity);
  if (!(dt > 0.0) || !std::isfinite(dt))
    return fail(Status::InvalidArgument, "viscosity: dt = %g must be positive and finite", dt);
  if (!sameGrid(grid.spec, fractions.grid))
    return fail(Status::InvalidArgument, "viscosity: the face fractions belong to another grid");
  w.solved = false;
  if (kinematicViscosity == 0.0) return Status::Ok;

  numberUnknowns(tasks, grid, fractions, liquidPhi, w);
  const int64_t n = w.axisBegin[3];
  if (stats != nullptr) stats->unknowns = n;
  if (n == 0) return Status::Ok;
  const double c = kinematicViscosity * dt / (grid.spec.h * grid.spec.h);
  for (Array<double>* v : {&w.open, &w.diagonal, &w.rhs, &w.velocity}) v->resize(static_cast<size_t>(n));

  parallelFor(tasks, n, kUnknownGrain, [&](int64_t begin, int64_t end) {
    for (int64_t u = begin; u < end; ++u) {
      const int a = axisOf(w, u);
      const Eigen::Vector3i f = faceCoords(grid.faceDims(a), w.face[static_cast<size_t>(u)]);
      w.open[static_cast<size_t>(u)] = effectiveOpenFraction(grid, fractions, a, f.x(), f.y(), f.z());
      w.velocity[static_cast<size_t>(u)] = grid.velocity[a][static_cast<size_t>(w.face[static_cast<size_t>(u)])];
    }
  });
  parallelFor(tasks, n, kUnknownGrain, [&](int64_t begin, int64_t end) {
    for (int64_t u = begin; u < end; ++u) {
      double diag = 0.0, boundary = 0.0;
      stencil(grid, fractions, liquidPhi, w, u, &diag, &boundary, [](int64_t, double) {});
      w.diagonal[static_cast<size_t>(u)] = 1.0 + c * diag;
      w.rhs[static_cast<size_t>(u)] = w.velocity[static_cast<size_t>(u)] + c * boundary;
    }
  });

  LinearSystem system;
  system.size = n;
  system.apply = [&](const double* x, double* y) {
    parallelFor(tasks, n, kUnknownGrain, [&](int64_t begin, int64_t end) {
      for (int64_t u = begin; u < end; ++u) {
        double offDiagonal = 0.0, unusedDiag, unusedBoundary;
        stencil(grid, fractions, liquidPhi, w, u, &unusedDiag, &unusedBoundary,
                [&](int64_t other, double coupling) { offDiagonal += coupling * x[other]; });
        y[u] = w.diagonal[static_cast<size_t>(u)] * x[u] - c * offDiagonal;
      }
    });
  };
  system.precondition = [&](const double* r, double* z) {
    parallelFor(tasks, n, kUnknownGrain, [&](int64_t begin, int64_t end) {
      for (int64_t u = begin; u < end; ++u) z[u] = r[u] / w.diagonal[static_cast<size_t>(u)];
    });
  };
  CgSettings cg;
  cg.relativeTolerance = settings.tolerance;
  cg.maxIterations = settings.maxIterations;
  cg.minIterations = settings.minIterations;
  const CgResult result = solveConjugateGradient(tasks, system, w.rhs.data(), w.velocity.data(), cg, deadline, w.cg);

  const bool record = settings.recordSolidExchange;
  if (record) {
    w.solidChange.resize(static_cast<size_t>(n));
    w.solidCoupling.resize(static_cast<size_t>(n));
  }
  parallelFor(tasks, n, kUnknownGrain, [&](int64_t begin, int64_t end) {
    for (int64_t u = begin; u < end; ++u) {
      const size_t i = static_cast<size_t>(u);
      grid.velocity[axisOf(w, u)][static_cast<size_t>(w.face[i])] = w.velocity[i];
      if (!record) continue;
      double unusedDiag, boundary, toSolids;
      stencil(grid, fractions, liquidPhi, w, u, &unusedDiag, &boundary, [](int64_t, double) {}, &toSolids);
      w.solidChange[i] = c * (boundary - toSolids * w.velocity[i]);
      w.solidCoupling[i] = c * toSolids;
    }
  });
  w.exchanged.clear();
  if (record)
    for (int64_t u = 0; u < n; ++u)
      if (w.solidChange[static_cast<size_t>(u)] != 0.0) w.exchanged.push_back(u);
  w.solved = record;
  if (stats != nullptr) stats->solve = result;
  return Status::Ok;
}

void forEachSolidExchange(const MacGrid& grid, const ViscosityWorkspace& w,
                          const std::function<void(int, const Eigen::Vector3i&, double, double)>& visit) {
  if (!w.solved) return;
  for (const int64_t u : w.exchanged) {
    const int a = axisOf(w, u);
    const size_t i = static_cast<size_t>(u);
    visit(a, faceCoords(grid.faceDims(a), w.face[i]), w.solidChange[i], w.solidCoupling[i]);
  }
}

}  // namespace vp
