// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/block_matrix.hpp"

namespace roifem::integrators {

SparseMatrix assemble_blocks(const std::vector<Index>& sizes, const std::vector<Block>& blocks, const SparseMatrix* pattern_of) {
  std::vector<Index> start(sizes.size() + 1, 0);
  for (std::size_t k = 0; k < sizes.size(); ++k) start[k + 1] = start[k] + sizes[k];
  std::vector<Eigen::Triplet<double>> t;
  for (const Block& b : blocks)
    for (Index j = 0; j < b.matrix->outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(*b.matrix, j); it; ++it)
        t.emplace_back(start[static_cast<std::size_t>(b.row)] + it.row(), start[static_cast<std::size_t>(b.col)] + it.col(),
                       b.scale * it.value());
  if (pattern_of)
    for (Index j = 0; j < pattern_of->outerSize(); ++j)
      for (SparseMatrix::InnerIterator it(*pattern_of, j); it; ++it) t.emplace_back(it.row(), it.col(), 0.0);
  SparseMatrix out(start.back(), start.back());
  out.setFromTriplets(t.begin(), t.end());
  out.makeCompressed();
  return out;
}

}  // namespace roifem::integrators
