#!/usr/bin/env bash
# SPDX-License-Identifier: LGPL-2.1-or-later
# Build VarSurf, check its style (clang-format, flake8), then run the C++ tests (ctest) and the
# Python/FreeCAD tests (pytest, on both cores), including the GUI smoke test under Xvfb and the
# Debian package's test; then the C++ tests again under AddressSanitizer and
# UndefinedBehaviorSanitizer, and each libFuzzer harness for a minute (tools/sanitize.sh). Exits
# non-zero if anything fails.
set -euo pipefail
cd "$(dirname "$0")/.."
bash tools/setup.sh
bash tools/build.sh
# OpenBLAS's worker threads spin while they wait, and two test processes on two cores then take
# the CPU from each other (measured on a hinge test: 33 CPU-seconds with its threads, 22 without).
export OPENBLAS_NUM_THREADS=1
# The sanitizer build (clang, some 18 core-minutes) starts now at the lowest priority, on the
# cycles the tests leave idle; tools/sanitize.sh finishes it (and reports its errors) at the end.
nice -n 19 bash tools/sanitize.sh --build-only > /dev/null 2>&1 &
early_build=$!

status=0
git ls-files -z '*.cpp' '*.hpp' | xargs -0 clang-format --dry-run --Werror || status=1
/usr/bin/python3 -m flake8 src tests bench examples tools Init.py InitGui.py || status=1
ctest --test-dir build --output-on-failure -j2 || status=1
# --dist loadfile: a test file's tests share one worker, so a module fixture runs once (the GUI
# smoke test's FreeCAD session writes one output folder; two workers running it raced on it).
/usr/bin/python3 -m pytest tests/python -q -p no:cacheprovider -n 2 --dist loadfile || status=1
wait "$early_build" || true  # a failed build fails again, with its log, just below
bash tools/sanitize.sh || status=1
exit $status
