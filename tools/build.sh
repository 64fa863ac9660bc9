#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Configure and build the C++ core, the OpenCASCADE bridge, the Python extension and the C++ tests
# in build/. The extension lands in src/varsurf/ so the workbench imports it in place.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release
cmake --build build -j2
