// SPDX-License-Identifier: LGPL-2.1-or-later
#include "free_block.hpp"

#include <string>

#include "varsurf/core/errors.hpp"

namespace varsurf {

FreeUnknowns free_unknowns(const std::vector<bool>& held) {
  FreeUnknowns f;
  f.slot.assign(held.size(), -1);
  for (size_t k = 0; k < held.size(); ++k)
    if (!held[k]) {
      f.slot[k] = static_cast<int>(f.free.size());
      f.free.push_back(static_cast<int>(k));
    }
  return f;
}

FreeUnknowns free_unknowns(int n, const std::vector<int>& held, const char* who) {
  std::vector<bool> mask(static_cast<size_t>(n), false);
  for (int k : held) {
    if (k < 0 || k >= n)
      throw InvalidInput(std::string(who) + ": a fixed pole index is out of range");
    mask[static_cast<size_t>(k)] = true;
  }
  return free_unknowns(mask);
}

Eigen::SparseMatrix<double> free_block(const Eigen::SparseMatrix<double>& a,
                                       const FreeUnknowns& f) {
  using Sparse = Eigen::SparseMatrix<double>;
  const int n = f.size();
  Sparse out(n, n);
  out.resizeNonZeros(a.nonZeros());  // at most; trimmed below
  int* outer = out.outerIndexPtr();
  int* inner = out.innerIndexPtr();
  double* values = out.valuePtr();
  int kept = 0;
  outer[0] = 0;
  for (int col = 0; col < a.outerSize(); ++col) {
    const int fc = f.slot[static_cast<size_t>(col)];
    if (fc < 0) continue;
    for (Sparse::InnerIterator it(a, col); it; ++it) {
      const int fr = f.slot[static_cast<size_t>(it.row())];
      if (fr < 0) continue;
      inner[kept] = fr;
      values[kept++] = it.value();
    }
    outer[fc + 1] = kept;
  }
  out.resizeNonZeros(kept);
  return out;
}

}  // namespace varsurf
