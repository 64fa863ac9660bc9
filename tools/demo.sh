#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Build VarSurf and run the demo: writes out/demo/{demo.FCStd,demo.step,demo.png,report.txt}.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
bash tools/build.sh
/usr/bin/python3 examples/demo.py out/demo
