#!/usr/bin/env bash
# Sets up, builds, and runs every test (unit tests in parallel, GL tests one at a time).
# With --full (first argument), then the sanitizer build (CMakePresets.json "asan": ASan +
# UBSan, build-asan/) with its tests, and the bounded fuzz runs (scripts/fuzz.sh): about 20
# minutes more on 2 cores, so CI does not run them yet (README, Tests). Other arguments go to
# the ctest runs.
set -euo pipefail
cd "$(dirname "$0")/.."
full=0
if [ "${1:-}" = --full ]; then
  full=1
  shift
fi
bash scripts/build.sh
(cd build && ctest --output-on-failure -j2 "$@")
[ "$full" = 1 ] || exit 0

# Sanitizers. The unit and editor-core tests all run, and the GL renderer tests; the slow GL
# groups (hard_*, every example project) and the real window (editor.window_smoke) are left to
# the normal run above, to keep CI within its time (README, Tests).
cmake --preset asan >/dev/null
cmake --build --preset asan --target glint_unit_tests glint_editor_tests glint_gl_tests
ctest --preset asan -R '^(unit\.|editor\.|gl\.GlRenderer\.|gl\.GlTextures\.)' \
      -E '^editor\.(window_smoke|Ui)' "$@"

bash scripts/fuzz.sh
