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
# Each stage says how long the run has taken so far, in wall-clock and in CPU time (user plus
# system of the finished commands, from /proc: cutime and cstime): on a shared machine the
# second is the steadier measure.
stage() {
  local stat
  read -ra stat </proc/$$/stat
  echo "== test.sh: $1 (${SECONDS} s so far, CPU $(((stat[15] + stat[16]) / $(getconf CLK_TCK))) s)" >&2
}
stage "build"
bash scripts/build.sh
stage "smoke render"
bash scripts/smoke_render.sh
stage "tests"
(cd build && ctest --output-on-failure -j2 "$@")
[ "$quick" = 1 ] && exit 0

# Sanitizers (README, Tests): every unit, editor and GL test but the real window
# (editor.window_smoke, editor.recovery_start and editor.state_files_start: they need the glint
# executable, not built here) and the scalability test
# unit.MalformedInput.AMillionSpheresLoad (minutes under ASan), the slower refractive chi-square
# cases (pure arithmetic), the soak (gl.Soak.*: it bounds heap and RSS, which ASan's allocator
# changes) and the frame-time test editor.BvhDrag.*
# (CMakePresets.json filters). The tests that make a GL context
# run with leak detection off (tests/sanitizers/lsan.supp says why).
stage "sanitizer build"
source scripts/compiler_cache.sh
cmake --preset asan >/dev/null
cmake --build --preset asan
stage "sanitizer tests"
ctest --preset asan "$@"
stage "sanitizer tests with GL"
ctest --preset asan-gl "$@"

stage "fuzzing"
bash scripts/fuzz.sh
stage "done"
