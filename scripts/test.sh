#!/usr/bin/env bash
# Sets up, builds, and runs every test (unit tests in parallel, GL tests one at a time), then
# the same test programs built with AddressSanitizer + UndefinedBehaviorSanitizer (the "asan"
# preset of CMakePresets.json, build-asan/) and the bounded fuzz runs (scripts/fuzz.sh). CI
# (.ci/run) runs exactly this. With --quick (first argument) only the normal build and tests
# run: the quick local loop. Other arguments go to the ctest runs.
set -euo pipefail
cd "$(dirname "$0")/.."
quick=0
if [ "${1:-}" = --quick ]; then
  quick=1
  shift
fi
stage() { echo "== test.sh: $1 ($SECONDS s so far)" >&2; }
stage "build"
bash scripts/build.sh
stage "tests"
(cd build && ctest --output-on-failure -j2 "$@")
[ "$quick" = 1 ] && exit 0

# Sanitizers: every unit.* and editor.* test, and the GL tests, except the real window
# (editor.window_smoke, which needs Xvfb and the glint executable, not built here) and the slow
# GL groups listed in the asan test preset (README, Tests).
stage "sanitizer build"
cmake --preset asan >/dev/null
cmake --build --preset asan
stage "sanitizer tests"
ctest --preset asan "$@"

stage "fuzzing"
bash scripts/fuzz.sh
stage "done"
