// Split cut cells: node-lattice components per cell, minor pieces' faces closed (see
// cut_cell_components.h).
#include "fluid/solids/cut_cell_components.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>
#include <vector>

#include "collide/mesh_lattice_signs.h"
#include "core/parallel_for.h"
#include "fluid/grid_index.h"
#include "fluid/solids/cell_box.h"

namespace vp {
namespace {

constexpr int kNodes = 8;  // per axis, corners included: spacing h / 7, 8 x 8 = 64 nodes per face
constexpr int kMaxColliders = 64;

struct SplitCell {
  int64_t cell;
  std::array<uint64_t, 6> mainNodes;  // per face 2 * axis + high: bit u + 8 v set where the node is in the main piece
};

// A convex collider at least this many cells wide everywhere splits no cell except near its
// edges and corners, where its two sides meet around the edge anyway (no leak): a slab splits
// a cell only when it is thinner than the cell's extent along its normal, at most sqrt(3) h.
constexpr double kThickWidthCells = 2.0;

// A lower bound on the collider's width (the smallest distance between two parallel planes
// enclosing it); infinite for a half-space, 0 for a mesh (not convex: no bound).
double minWidthLowerBound(const PreparedCollider& c) {
  const ColliderShape& s = c.shape;
  switch (s.kind) {
    case ShapeKind::Sphere:
    case ShapeKind::Capsule: return 2.0 * s.radius;
    case ShapeKind::Cylinder: return 2.0 * std::min(s.radius, s.halfHeight);
    case ShapeKind::Box: return 2.0 * s.halfExtents.minCoeff();
    case ShapeKind::Plane: return std::numeric_limits<double>::infinity();
    case ShapeKind::ConvexHull: {
      // The hull holds the ball around its points' centroid out to the nearest face plane,
      // and no strip thinner than that ball's diameter holds the hull.
      if (s.hullPoints.empty() || c.localPlanes.empty()) return 0.0;
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      for (const Eigen::Vector3d& p : s.hullPoints) centroid += p;
      centroid /= static_cast<double>(s.hullPoints.size());
      double depth = std::numeric_limits<double>::infinity();
      for (const Eigen::Vector4d& plane : c.localPlanes)
        depth = std::min(depth, (plane.w() - plane.head<3>().dot(centroid)) / plane.head<3>().norm());
      return std::max(0.0, 2.0 * depth);
    }
    case ShapeKind::TriangleMesh: return 0.0;
  }
  return 0.0;
}

size_t cellIndex(const MacGridSpec& g, int i, int j, int k) {
  return static_cast<size_t>(i) + static_cast<size_t>(g.nx) * (j + static_cast<size_t>(g.ny) * k);
}

// The cell's nodes as 8 layers (one per z node) of 64 bits, bit x + 8 y.
using NodeMask = std::array<uint64_t, kNodes>;

// Open nodes of the cell: signed distance > 0 for every collider. A block of nodes whose
// centre is farther from the surface than the block's half-diagonal takes the centre's sign
// (the distance bounds are 1-Lipschitz), so only blocks the surface passes near are refined.
class NodeSampler {
 public:
  NodeSampler(const PreparedCollider* const* colliders, int count, const MacGridSpec& grid, const Eigen::Vector3d& cell)
      : colliders_(colliders), count_(count), grid_(grid), cell_(cell), step_(grid.h / (kNodes - 1)) {}

  NodeMask sample() {
    NodeMask open{};
    block(open, 0, 0, 0, kNodes);
    return open;
  }

 private:
  double distance(const Eigen::Vector3d& x) const {
    double d = std::numeric_limits<double>::infinity();
    for (int c = 0; c < count_; ++c) d = std::min(d, signedDistanceBound(*colliders_[c], x));
    return d;
  }
  // Node position from node coordinates: a node on a face shared by two cells gets bitwise
  // the same position from both (i + 7 / 7 == (i + 1) + 0 / 7), so both read the same sign.
  Eigen::Vector3d node(double a, double b, double c) const {
    return grid_.origin + grid_.h * (cell_ + Eigen::Vector3d(a, b, c) / (kNodes - 1));
  }

  static void set(NodeMask& open, int a0, int b0, int c0, int size) {
    const uint64_t row = ((uint64_t(1) << size) - 1) << a0;
    uint64_t layer = 0;
    for (int b = b0; b < b0 + size; ++b) layer |= row << (kNodes * b);
    for (int c = c0; c < c0 + size; ++c) open[static_cast<size_t>(c)] |= layer;
  }

  void block(NodeMask& open, int a0, int b0, int c0, int size) {
    if (size == 1) {
      if (distance(node(a0, b0, c0)) > 0.0) set(open, a0, b0, c0, 1);
      return;
    }
    const double half = 0.5 * (size - 1);
    const double d = distance(node(a0 + half, b0 + half, c0 + half));
    if (std::abs(d) > half * step_ * std::sqrt(3.0)) {
      if (d > 0.0) set(open, a0, b0, c0, size);
      return;
    }
    const int s = size / 2;
    for (int q = 0; q < 8; ++q) block(open, a0 + (q & 1) * s, b0 + ((q >> 1) & 1) * s, c0 + ((q >> 2) & 1) * s, s);
  }

  const PreparedCollider* const* colliders_;
  int count_;
  const MacGridSpec& grid_;
  Eigen::Vector3d cell_;  // the cell's integer index
  double step_;
};

// The open nodes connected to `seed` through lattice edges (6-neighbours), by bit-parallel
// growth: each round adds every open neighbour of the set, layer by layer.
NodeMask floodFill(const NodeMask& open, const NodeMask& seed) {
  NodeMask reached = seed;
  constexpr uint64_t kNotFirstColumn = ~uint64_t(0x0101010101010101);  // x > 0
  constexpr uint64_t kNotLastColumn = ~uint64_t(0x8080808080808080);   // x < 7
  for (bool grew = true; grew;) {
    grew = false;
    NodeMask next;
    for (int z = 0; z < kNodes; ++z) {
      const uint64_t r = reached[static_cast<size_t>(z)];
      uint64_t g = r | ((r << 1) & kNotFirstColumn) | ((r >> 1) & kNotLastColumn) | (r << kNodes) | (r >> kNodes);
      if (z > 0) g |= reached[static_cast<size_t>(z - 1)];
      if (z + 1 < kNodes) g |= reached[static_cast<size_t>(z + 1)];
      next[static_cast<size_t>(z)] = g & open[static_cast<size_t>(z)];
      grew = grew || next[static_cast<size_t>(z)] != r;
    }
    reached = next;
  }
  return reached;
}

int popcount(const NodeMask& m) {
  int n = 0;
  for (uint64_t layer : m) n += __builtin_popcountll(layer);
  return n;
}

// The 64 nodes of face (2 * axis + high) as bits u + 8 v, u along axis + 1, v along axis + 2
// (mod 3): the same bits from the cells on both sides of the face.
uint64_t faceNodes(const NodeMask& m, int axis, int high) {
  const int end = high ? kNodes - 1 : 0;
  uint64_t out = 0;
  if (axis == 2) return m[static_cast<size_t>(end)];  // u = x, v = y: the layer itself
  for (int v = 0; v < kNodes; ++v)
    for (int u = 0; u < kNodes; ++u) {
      int p[3];
      p[axis] = end, p[(axis + 1) % 3] = u, p[(axis + 2) % 3] = v;
      if ((m[static_cast<size_t>(p[2])] >> (p[0] + kNodes * p[1])) & 1) out |= uint64_t(1) << (u + kNodes * v);
    }
  return out;
}

// True when one convex collider certainly leaves the cell in one piece. Every piece of a cube
// minus a convex solid holds a corner of the cube (a plane separating a point of the piece
// from the solid cuts off a part of the cube that holds a corner and misses the solid), and
// two open corners whose distances add up to more than their separation see each other
// through open space (the balls the 1-Lipschitz distance bound clears cover the segment).
// So when those segments join all open corners, there is one piece.
bool convexLeavesOnePiece(const PreparedCollider& collider, const Eigen::Vector3d& low, double h) {
  double d[8];
  Eigen::Vector3d x[8];
  int open = 0;
  for (int q = 0; q < 8; ++q) {
    x[q] = low + h * Eigen::Vector3d(q & 1, (q >> 1) & 1, (q >> 2) & 1);
    d[q] = signedDistanceBound(collider, x[q]);
    open += d[q] > 0.0;
  }
  if (open <= 1) return true;
  unsigned group[8];
  for (int q = 0; q < 8; ++q) group[q] = d[q] > 0.0 ? 1u << q : 0u;
  // Joins by repeated passes over the 28 pairs (8 corners: a few passes at most).
  for (bool changed = true; changed;) {
    changed = false;
    for (int p = 0; p < 8; ++p)
      for (int q = p + 1; q < 8; ++q) {
        if (!(d[p] > 0.0) || !(d[q] > 0.0) || group[p] == group[q]) continue;
        if (d[p] + d[q] > (x[p] - x[q]).norm()) {
          const unsigned joined = group[p] | group[q];
          for (int r = 0; r < 8; ++r)
            if (group[r] & joined) group[r] = joined;
          changed = true;
        }
      }
  }
  unsigned first = 0;
  for (int q = 0; q < 8; ++q)
    if (d[q] > 0.0) {
      if (first == 0) first = group[q];
      else if (group[q] != first) return false;
    }
  return true;
}

// The cell's open nodes. A mesh's signs come from crossings along the lattice lines
// (collide/mesh_lattice_signs.h: a few hundred of its signed distances cost far more), the
// other colliders' from the sampler; where the crossings do not decide, the sampler does all.
NodeMask openNodes(const PreparedCollider* const* colliders, int count, const MacGridSpec& grid,
                   const Eigen::Vector3d& cell) {
  const PreparedCollider* others[kMaxColliders];
  int rest = 0;
  NodeMask open;
  open.fill(~uint64_t(0));
  for (int c = 0; c < count; ++c) {
    if (colliders[c]->shape.kind != ShapeKind::TriangleMesh) {
      others[rest++] = colliders[c];
      continue;
    }
    NodeMask outside;
    if (!latticeNodesOutsideMesh(*colliders[c], grid.origin, grid.h, cell, &outside))
      return NodeSampler(colliders, count, grid, cell).sample();
    for (int z = 0; z < kNodes; ++z) open[static_cast<size_t>(z)] &= outside[static_cast<size_t>(z)];
  }
  if (rest == count) return NodeSampler(colliders, count, grid, cell).sample();
  if (rest > 0) {
    const NodeMask sampled = NodeSampler(others, rest, grid, cell).sample();
    for (int z = 0; z < kNodes; ++z) open[static_cast<size_t>(z)] &= sampled[static_cast<size_t>(z)];
  }
  return open;
}

// Fills `out` and returns true when the cell's open nodes form two or more pieces that reach
// the cell's boundary.
bool sampleSplitCell(const PreparedCollider* const* colliders, int count, const MacGridSpec& grid,
                     const Eigen::Vector3d& cell, SplitCell* out) {
  const NodeMask open = openNodes(colliders, count, grid, cell);
  // Open nodes on the cell's boundary not yet in a piece.
  constexpr uint64_t kRing = 0xFF818181818181FF;  // x or y at 0 or 7
  NodeMask left;
  for (int z = 0; z < kNodes; ++z)
    left[static_cast<size_t>(z)] = open[static_cast<size_t>(z)] & (z == 0 || z == kNodes - 1 ? ~uint64_t(0) : kRing);
  NodeMask main{};
  int mainSize = 0, pieces = 0;
  for (int z = 0; z < kNodes; ++z) {
    while (left[static_cast<size_t>(z)] != 0) {
      NodeMask seed{};
      seed[static_cast<size_t>(z)] = left[static_cast<size_t>(z)] & (~left[static_cast<size_t>(z)] + 1);  // lowest bit
      const NodeMask piece = floodFill(open, seed);
      for (int l = 0; l < kNodes; ++l) left[static_cast<size_t>(l)] &= ~piece[static_cast<size_t>(l)];
      ++pieces;
      const int size = popcount(piece);
      if (size > mainSize) main = piece, mainSize = size;
    }
  }
  if (pieces < 2) return false;
  for (int a = 0; a < 3; ++a)
    for (int high = 0; high < 2; ++high) out->mainNodes[static_cast<size_t>(2 * a + high)] = faceNodes(main, a, high);
  return true;
}

// One pass over a box: the cells' rows are sampled (in parallel: a row writes only its own
// entries and reads face fractions the pass leaves alone), then the split cells' faces are
// closed in cell order. Kept alive by the passes that use it.
class SplitCellPass {
 public:
  SplitCellPass(const PreparedCollider* const* colliders, int count, const Aabb& box, FaceFractionField* field,
                CutCellComponentStats* stats)
      : colliders_(colliders), count_(count), field_(field), stats_(stats) {
    const MacGridSpec& g = field->grid;
    // Decisions are made for the cells around the box; their neighbours (one more layer) are
    // sampled too, since a face's decision reads both cells.
    apply_ = cellBoxAround(g, box, 0);
    sampled_ = cellBoxAround(g, box, 1);
    const int rows = apply_.empty() ? 0 : (sampled_.hi[1] - sampled_.lo[1] + 1) * (sampled_.hi[2] - sampled_.lo[2] + 1);
    rowCandidates_.resize(static_cast<size_t>(rows));
    thin_.resize(static_cast<size_t>(count));
    for (int c = 0; c < count; ++c)
      thin_[static_cast<size_t>(c)] = minWidthLowerBound(*colliders[c]) < kThickWidthCells * g.h;
  }
  int64_t rows() const { return static_cast<int64_t>(rowCandidates_.size()); }
  int rowLength() const { return sampled_.hi[0] - sampled_.lo[0] + 1; }
  int64_t candidates() const { return static_cast<int64_t>(candidates_.size()); }

  // Lists the rows' cells that need sampling (rowCandidates_).
  void findCandidates(int64_t beginRow, int64_t endRow);
  // Joins the rows' lists in row order (so in cell order) and sizes the samples' results.
  void gatherCandidates();
  void sampleCandidates(int64_t begin, int64_t end);
  void closeMinorPieces();

 private:
  const SplitCell* findSplit(int64_t cell) const {
    auto it = std::lower_bound(split_.begin(), split_.end(), cell,
                               [](const SplitCell& s, int64_t c) { return s.cell < c; });
    return it != split_.end() && it->cell == cell ? &*it : nullptr;
  }
  // The colliders whose bounds meet cell (i, j, k), at most kMaxColliders; anyThin: one of
  // them is thin.
  int nearColliders(int i, int j, int k, const PreparedCollider** near, bool* anyThin) const;

  const PreparedCollider* const* colliders_;
  int count_;
  FaceFractionField* field_;
  CutCellComponentStats* stats_;
  CellBox apply_, sampled_;
  Array<uint8_t> thin_;
  std::vector<Array<int64_t>> rowCandidates_;
  Array<int64_t> candidates_;
  Array<SplitCell> samples_;
  Array<uint8_t> isSplit_;
  Array<SplitCell> split_;
};

int SplitCellPass::nearColliders(int i, int j, int k, const PreparedCollider** near, bool* anyThin) const {
  const MacGridSpec& g = field_->grid;
  Aabb cellBounds;
  cellBounds.lo = g.origin + g.h * Eigen::Vector3d(i, j, k);
  cellBounds.hi = g.origin + g.h * Eigen::Vector3d(i + 1, j + 1, k + 1);
  int n = 0;
  *anyThin = false;
  for (int c = 0; c < count_ && n < kMaxColliders; ++c)
    if (colliders_[c]->bounds.overlaps(cellBounds)) {
      near[n++] = colliders_[c];
      *anyThin = *anyThin || thin_[static_cast<size_t>(c)];
    }
  return n;
}

void SplitCellPass::findCandidates(int64_t beginRow, int64_t endRow) {
  const MacGridSpec& g = field_->grid;
  FaceFractionField& f = *field_;
  const PreparedCollider* near[kMaxColliders];
  for (int64_t row = beginRow; row < endRow; ++row) {
    const int j = sampled_.lo[1] + static_cast<int>(row % (sampled_.hi[1] - sampled_.lo[1] + 1));
    const int k = sampled_.lo[2] + static_cast<int>(row / (sampled_.hi[1] - sampled_.lo[1] + 1));
    Array<int64_t>& list = rowCandidates_[static_cast<size_t>(row)];
    list.clear();
    for (int i = sampled_.lo[0]; i <= sampled_.hi[0]; ++i) {
      bool allOpen = true, allClosed = true;
      for (int face = 0; face < 6; ++face) {
        const double o = faceOpen(f, i, j, k, face);
        allOpen = allOpen && o >= 1.0;
        allClosed = allClosed && o <= 0.0;
      }
      if (allOpen || allClosed) continue;
      bool anyThin = false;
      const int n = nearColliders(i, j, k, near, &anyThin);
      // One thick collider splits the cell only around one of its edges (kThickWidthCells),
      // unless a domain side closes the way round; several colliders can meet in a thin wall.
      const bool onDomainSide = i == 0 || j == 0 || k == 0 || i == g.nx - 1 || j == g.ny - 1 || k == g.nz - 1;
      if (n == 0 || (n == 1 && !anyThin && !onDomainSide)) continue;
      const Eigen::Vector3d low = g.origin + g.h * Eigen::Vector3d(i, j, k);
      if (n == 1 && near[0]->shape.kind != ShapeKind::TriangleMesh && convexLeavesOnePiece(*near[0], low, g.h))
        continue;
      list.push_back(static_cast<int64_t>(cellIndex(g, i, j, k)));
    }
  }
}

void SplitCellPass::gatherCandidates() {
  candidates_.clear();
  for (const Array<int64_t>& list : rowCandidates_) candidates_.insert(candidates_.end(), list.begin(), list.end());
  samples_.resize(candidates_.size());
  isSplit_.resize(candidates_.size());
}

void SplitCellPass::sampleCandidates(int64_t begin, int64_t end) {
  const MacGridSpec& g = field_->grid;
  const PreparedCollider* near[kMaxColliders];
  for (int64_t c = begin; c < end; ++c) {
    const int64_t cell = candidates_[static_cast<size_t>(c)];
    const int i = static_cast<int>(cell % g.nx), j = static_cast<int>((cell / g.nx) % g.ny),
              k = static_cast<int>(cell / (static_cast<int64_t>(g.nx) * g.ny));
    bool anyThin = false;
    const int n = nearColliders(i, j, k, near, &anyThin);
    SplitCell& s = samples_[static_cast<size_t>(c)];
    s.cell = cell;
    isSplit_[static_cast<size_t>(c)] = sampleSplitCell(near, n, g, Eigen::Vector3d(i, j, k), &s) ? 1 : 0;
  }
}

void SplitCellPass::closeMinorPieces() {
  const MacGridSpec& g = field_->grid;
  FaceFractionField& f = *field_;
  // The candidates are in cell order, so split_ is sorted by cell.
  split_.clear();
  for (size_t c = 0; c < candidates_.size(); ++c)
    if (isSplit_[c]) split_.push_back(samples_[c]);
  const int64_t cut = candidates();
  int64_t closed = 0, splitApplied = 0;
  const int cells[3] = {g.nx, g.ny, g.nz};
  for (const SplitCell& s : split_) {
    const int i = static_cast<int>(s.cell % g.nx), j = static_cast<int>((s.cell / g.nx) % g.ny),
              k = static_cast<int>(s.cell / (static_cast<int64_t>(g.nx) * g.ny));
    const int at[3] = {i, j, k};
    bool inApply = true;
    for (int d = 0; d < 3; ++d) inApply = inApply && at[d] >= apply_.lo[d] && at[d] <= apply_.hi[d];
    if (!inApply) continue;
    ++splitApplied;
    for (int face = 0; face < 6; ++face) {
      double& open = faceOpen(f, i, j, k, face);
      if (!(open > 0.0)) continue;
      const int a = face / 2, high = face & 1;
      uint64_t shared = s.mainNodes[static_cast<size_t>(face)];
      Eigen::Vector3i nb(i, j, k);
      nb[a] += high ? 1 : -1;
      if (nb[a] >= 0 && nb[a] < cells[a]) {
        // The neighbour sees the same face as its opposite face, with the same node bits.
        if (const SplitCell* other = findSplit(static_cast<int64_t>(cellIndex(g, nb.x(), nb.y(), nb.z()))))
          shared &= other->mainNodes[static_cast<size_t>(2 * a + (1 - high))];
      }
      if (shared == 0) {
        open = 0.0;
        ++closed;
      }
    }
  }
  if (stats_ != nullptr) {
    stats_->cutCells = cut;
    stats_->splitCells = splitApplied;
    stats_->closedFaces = closed;
  }
}

Status checkSplitCellArgs(int count, const PreparedCollider* const* colliders, const FaceFractionField* field) {
  if (field == nullptr) return fail(Status::InvalidArgument, "split cut cells: field is null");
  if (count < 0 || (count > 0 && colliders == nullptr))
    return fail(Status::InvalidArgument, "split cut cells: colliders null or count %d < 0", count);
  return Status::Ok;
}

// Checking a cell for cut faces and near colliders costs about this many of the samples that
// bound a slice (an advection sample); sampling a listed cell on the node lattice costs
// kSamplesPerSampledCell. The sampled cells are a pass of their own, so that a slice's samples
// stand for its cost: spread over the rows, a few rows along a mesh cost many slices' worth.
constexpr int64_t kSamplesPerCheckedCell = 2;
constexpr int64_t kSamplesPerSampledCell = 8192;
constexpr int64_t kCheckedRowGrain = 4;
constexpr int64_t kSampledCellGrain = 1;

}  // namespace

Status closeSplitCellPieces(TaskSystem& tasks, const PreparedCollider* const* colliders, int count, const Aabb& box,
                            FaceFractionField* field, CutCellComponentStats* stats) {
  SlabPasses passes(tasks);
  VP_TRY(addSplitCellPasses(passes, colliders, count, box, field, stats));
  passes.runAll();
  return Status::Ok;
}

Status addSplitCellPasses(SlabPasses& passes, const PreparedCollider* const* colliders, int count, const Aabb& box,
                          FaceFractionField* field, CutCellComponentStats* stats) {
  VP_TRY(checkSplitCellArgs(count, colliders, field));
  if (stats != nullptr) *stats = CutCellComponentStats{};
  if (count == 0 || box.empty()) return Status::Ok;
  auto pass = std::make_shared<SplitCellPass>(colliders, count, box, field, stats);
  if (pass->rows() == 0) return Status::Ok;
  passes.addParallel(pass->rows(), pass->rowLength() * kSamplesPerCheckedCell, kCheckedRowGrain,
                     [pass](int64_t begin, int64_t end) { pass->findCandidates(begin, end); });
  SlabPasses* list = &passes;
  passes.addStep([pass, list] {
    pass->gatherCandidates();
    list->addParallel(pass->candidates(), kSamplesPerSampledCell, kSampledCellGrain,
                      [pass](int64_t begin, int64_t end) { pass->sampleCandidates(begin, end); });
    list->addWhole(pass->rowLength() * pass->rows(), [pass] { pass->closeMinorPieces(); });
  });
  return Status::Ok;
}

}  // namespace vp
