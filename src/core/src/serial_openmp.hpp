// SPDX-License-Identifier: LGPL-2.1-or-later
// OpenMP parallel regions opened by the libraries a solve calls run on one thread for the life of
// this guard.
//
// Why: CHOLMOD's supernodal factorization opens OpenMP regions with a thread count of its own,
// which OMP_NUM_THREADS does not lower; on a 2-core machine its threads spend the factorization
// waking and waiting for each other. Measured on the 64 x 64 penalty matrix of benchmark 3
// (4096 unknowns, 91 Mflop): 60 ms with those threads, 8 ms on one; 256 x 256 (10 Gflop):
// 1.44 s against 0.42 s. Two threads were no faster than one (0.46 s).
#pragma once

namespace varsurf {

class SerialOpenMp {
 public:
  SerialOpenMp();
  ~SerialOpenMp();
  SerialOpenMp(const SerialOpenMp&) = delete;
  SerialOpenMp& operator=(const SerialOpenMp&) = delete;

 private:
  int saved_levels_;
};

}  // namespace varsurf
