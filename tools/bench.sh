#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Build VarSurf and print the benchmark tables (bench/run_bench.py; --quick stops at 64 x 64).
# --callgrind also counts the instructions of benchmark 2's recomputes under valgrind
# (bench/callgrind_filling.py; installs valgrind if it is missing).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
bash tools/build.sh
args=()
callgrind=0
for arg in "$@"; do
  if [ "$arg" = "--callgrind" ]; then callgrind=1; else args+=("$arg"); fi
done
/usr/bin/python3 bench/run_bench.py "${args[@]}"
if [ "$callgrind" = 1 ]; then
  if ! command -v valgrind > /dev/null; then
    SUDO=""
    [ "$(id -u)" -ne 0 ] && SUDO="sudo"
    $SUDO apt-get update -qq && $SUDO apt-get install -y -qq --no-install-recommends valgrind
  fi
  echo
  echo "## 2b. Instructions executed by one warm recompute (callgrind), same cases"
  echo
  /usr/bin/python3 bench/callgrind_filling.py
fi
