#!/usr/bin/env bash
# Sets up, builds, and runs every test (unit tests in parallel, GL tests one at a time).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
cd build
ctest --output-on-failure -j2 "$@"
