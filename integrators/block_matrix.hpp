// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
/// Sparse matrices assembled from blocks, as the first-order and DAE forms need them
/// ([[0, I], [-M^-1 K, -M^-1 C]], IDA's dF/dy and dF/dy', ...).
#include <vector>

#include "common/types.hpp"

namespace roifem::integrators {

struct Block {
  int row = 0, col = 0;        ///< block position
  const SparseMatrix* matrix;  ///< its entries
  double scale = 1.0;
};

/// The matrix whose block (r, c) has sizes[r] x sizes[c] entries from the listed blocks (others
/// zero). With `pattern_of`, every entry of that matrix is present too (an explicit zero where no
/// block puts a value), so that two matrices built against each other share one pattern.
SparseMatrix assemble_blocks(const std::vector<Index>& sizes, const std::vector<Block>& blocks,
                             const SparseMatrix* pattern_of = nullptr);

}  // namespace roifem::integrators
