#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Build VarSurf and print the benchmark tables (bench/run_bench.py; --quick stops at 64 x 64).
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
bash tools/build.sh
/usr/bin/python3 bench/run_bench.py "$@"
