#include "linalg/block_sparse_matrix.h"

#include <algorithm>

#include "core/parallel_for.h"
#include "gpu_kernels/block_row_kernels.h"

namespace vp {

template <class Scalar>
int32_t BlockSparseMatrix<Scalar>::find(int32_t row, int32_t column) const {
  const int32_t* begin = columns.data() + rowStart[row];
  const int32_t* end = columns.data() + rowStart[row + 1];
  const int32_t* it = std::lower_bound(begin, end, column);
  return it != end && *it == column ? static_cast<int32_t>(it - columns.data()) : -1;
}

template <class Scalar>
void BlockSparseMatrix<Scalar>::setZero() {
  std::fill(values.begin(), values.end(), Scalar(0));
}

template <class Scalar>
void BlockSparseMatrix<Scalar>::multiply(TaskSystem& tasks, const double* x, double* y) const {
  parallelFor(tasks, blockRows, 512, [&](int64_t rowBegin, int64_t rowEnd) {
    for (int64_t r = rowBegin; r < rowEnd; ++r)
      kernels::bcsrRowProduct(r, rowStart.data(), columns.data(), values.data(), x, y);
  });
}

template <class Scalar>
void buildElementPattern(int32_t nodeCount, const int32_t* elementNodes, int64_t elementCount, int nodesPerElement,
                         BlockSparseMatrix<Scalar>* matrix, Array<int32_t>* scatter) {
  const int n = nodesPerElement;
  // Node -> incident elements (CSR), then each row's neighbour set sorted and deduplicated.
  Array<int32_t> incidenceStart(static_cast<size_t>(nodeCount) + 1, 0);
  for (int64_t i = 0; i < elementCount * n; ++i) incidenceStart[elementNodes[i] + 1]++;
  for (int32_t v = 0; v < nodeCount; ++v) incidenceStart[v + 1] += incidenceStart[v];
  Array<int32_t> incidence(static_cast<size_t>(incidenceStart[nodeCount]));
  Array<int32_t> fill(incidenceStart.begin(), incidenceStart.end() - 1);
  for (int64_t e = 0; e < elementCount; ++e)
    for (int a = 0; a < n; ++a) incidence[fill[elementNodes[e * n + a]]++] = static_cast<int32_t>(e);

  BlockSparseMatrix<Scalar>& m = *matrix;
  m.blockRows = nodeCount;
  m.rowStart.assign(static_cast<size_t>(nodeCount) + 1, 0);
  m.columns.clear();
  Array<int32_t> neighbours;
  for (int32_t v = 0; v < nodeCount; ++v) {
    neighbours.clear();
    neighbours.push_back(v);  // every row has its diagonal, even for an isolated node
    for (int32_t k = incidenceStart[v]; k < incidenceStart[v + 1]; ++k)
      for (int a = 0; a < n; ++a) neighbours.push_back(elementNodes[static_cast<int64_t>(incidence[k]) * n + a]);
    std::sort(neighbours.begin(), neighbours.end());
    neighbours.erase(std::unique(neighbours.begin(), neighbours.end()), neighbours.end());
    m.columns.insert(m.columns.end(), neighbours.begin(), neighbours.end());
    m.rowStart[v + 1] = static_cast<int32_t>(m.columns.size());
  }
  m.values.assign(m.columns.size() * 9, Scalar(0));
  m.diagonal.resize(static_cast<size_t>(nodeCount));
  for (int32_t v = 0; v < nodeCount; ++v) m.diagonal[v] = m.find(v, v);

  scatter->resize(static_cast<size_t>(elementCount) * n * n);
  for (int64_t e = 0; e < elementCount; ++e)
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        (*scatter)[static_cast<size_t>((e * n + a) * n + b)] =
            m.find(elementNodes[e * n + a], elementNodes[e * n + b]);
}

template struct BlockSparseMatrix<float>;
template struct BlockSparseMatrix<double>;
template void buildElementPattern<float>(int32_t, const int32_t*, int64_t, int, BlockSparseMatrix<float>*,
                                         Array<int32_t>*);
template void buildElementPattern<double>(int32_t, const int32_t*, int64_t, int, BlockSparseMatrix<double>*,
                                          Array<int32_t>*);

}  // namespace vp
