#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Build VarSurf, then run the C++ tests (ctest) and the Python/FreeCAD tests (pytest), including
# the GUI smoke test under Xvfb; then the C++ tests again under AddressSanitizer and
# UndefinedBehaviorSanitizer, and each libFuzzer harness for a minute (tools/sanitize.sh). Exits
# non-zero if anything fails.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
bash tools/build.sh

status=0
ctest --test-dir build --output-on-failure -j2 || status=1
/usr/bin/python3 -m pytest tests/python -q -p no:cacheprovider || status=1
bash tools/sanitize.sh || status=1
exit $status
