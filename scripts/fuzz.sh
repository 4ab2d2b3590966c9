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

# Bounded by executions, with a time cap as a safety net. At about 25k exec/s (measured on this
# 2-core machine) 10^6 project inputs take about 40 s; the image readers are slower per input,
# so they get 2*10^5 in about 20 s.
project_runs=${GLINT_FUZZ_PROJECT_RUNS:-1000000}
image_runs=${GLINT_FUZZ_IMAGE_RUNS:-200000}
seconds=${GLINT_FUZZ_SECONDS:-}
mkdir -p build-fuzz/artifacts
status=0
run() {
  local target=$1 runs=$2 max_len=$3
  local work=build-fuzz/corpus/$target
  mkdir -p "$work"
  local limits=(-runs="$runs" -max_total_time=120)
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
run fuzz_project "$project_runs" 8192
run fuzz_image "$image_runs" 4096
[ $status -eq 0 ] && echo "fuzz: no crashes" >&2
exit $status
