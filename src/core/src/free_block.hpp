// SPDX-License-Identifier: LGPL-2.1-or-later
// The free unknowns of a system some of whose unknowns are held, and the block of a sparse
// symmetric matrix on them: shared by the constrained solve, the multigrid and the dynamics.
#pragma once

#include <Eigen/SparseCore>
#include <vector>

namespace varsurf {

struct FreeUnknowns {
  std::vector<int> slot;  // unknown -> its index among the free ones, or -1 if held
  std::vector<int> free;  // the free unknowns in increasing order
  int size() const { return static_cast<int>(free.size()); }
};

// Which of `n` unknowns are free when `held[k]` says whether unknown k is held.
FreeUnknowns free_unknowns(const std::vector<bool>& held);

// The same from a list of held indices; InvalidInput naming `who` for an index out of range.
FreeUnknowns free_unknowns(int n, const std::vector<int>& held, const char* who);

// a's rows and columns of the free unknowns (an n_free x n_free matrix). Free indices keep the
// unknowns' order, so the block is written straight into compressed storage (collecting
// triplets and sorting them took 90 ms at 256 x 256 poles).
Eigen::SparseMatrix<double> free_block(const Eigen::SparseMatrix<double>& a, const FreeUnknowns& f);

}  // namespace varsurf
