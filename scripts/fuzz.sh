#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) in build-fuzz/ and runs each for a
# bounded number of inputs from the seed corpus in tests/fuzz/corpus (new inputs go to
# build-fuzz/corpus, never into the repository). Exits non-zero on any crash, sanitizer report
# or leak; the input that caused it is saved as build-fuzz/artifacts/crash-*.
#   bash scripts/fuzz.sh                      # the CI run: about a minute in all
#   GLINT_FUZZ_SECONDS=600 bash scripts/fuzz.sh   # longer: each target runs for that long
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz

# The project loader is bounded by executions (10^6), with a time cap as a safety net; the
# image readers by time. Measured here (2 shared cores, ASan + UBSan, while other builds ran):
# 1.1k to 2.8k project inputs per second, so 10^6 take several minutes on this machine, more
# than the minute hoped for: lower GLINT_FUZZ_PROJECT_RUNS for a quicker local run.
project_runs=${GLINT_FUZZ_PROJECT_RUNS:-1000000}
image_seconds=${GLINT_FUZZ_IMAGE_SECONDS:-30}
seconds=${GLINT_FUZZ_SECONDS:-}
mkdir -p build-fuzz/artifacts
status=0
run() {
  local target=$1 max_len=$2
  shift 2
  local work=build-fuzz/corpus/$target
  mkdir -p "$work"
  local limits=("$@")
  [ -n "$seconds" ] && limits=(-max_total_time="$seconds")
  echo "fuzz: $target ${limits[*]}" >&2
  # rss_limit: 2 GiB per input at most (the loaders refuse images over 16384 per side).
  if ! "build-fuzz/tests/fuzz/$target" "${limits[@]}" -max_len="$max_len" -rss_limit_mb=2560 \
        -artifact_prefix=build-fuzz/artifacts/ -print_final_stats=1 \
        "$work" "tests/fuzz/corpus/${target#fuzz_}" 2>build-fuzz/$target.log; then
    status=1
    tail -n 60 build-fuzz/$target.log >&2
  fi
  grep -E "^Done|stat::number_of_executed_units|stat::average_exec_per_sec" build-fuzz/$target.log >&2 || true
}
run fuzz_project 8192 -runs="$project_runs" -max_total_time=900
run fuzz_image 4096 -max_total_time="$image_seconds"
[ $status -eq 0 ] && echo "fuzz: no crashes" >&2
exit $status
