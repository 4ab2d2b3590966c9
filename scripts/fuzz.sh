#!/usr/bin/env bash
# Builds the libFuzzer targets with clang (ASan + UBSan) in build-fuzz/ and runs each for a
# bounded number of inputs from the corpus in tests/fuzz/corpus (new inputs go to
# build-fuzz/corpus; see the README for merging them into the repository). Exits non-zero on
# any crash, sanitizer report or leak (the input is saved as build-fuzz/artifacts/crash-*), and
# when the project loader ran fewer than its 3 x 10^5 inputs.
#   bash scripts/fuzz.sh                           # the CI run (scripts/test.sh)
#   GLINT_FUZZ_SECONDS=600 bash scripts/fuzz.sh    # longer: each target runs for that long
# Each target runs as GLINT_FUZZ_WORKERS processes (default: the number of cores) that share
# one corpus folder (libFuzzer reloads it, so each sees what the others found).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
source scripts/compiler_cache.sh
cmake --preset fuzz >/dev/null
cmake --build --preset fuzz

project_runs=${GLINT_FUZZ_PROJECT_RUNS:-300000}
image_seconds=${GLINT_FUZZ_IMAGE_SECONDS:-30}
seconds=${GLINT_FUZZ_SECONDS:-}
workers=${GLINT_FUZZ_WORKERS:-$(nproc)}
mkdir -p build-fuzz/artifacts
status=0

# run TARGET MAX_LEN MIN_RUNS LIMIT...: the workers in parallel, then their stats.
run() {
  local target=$1 max_len=$2 min_runs=$3
  shift 3
  local work=build-fuzz/corpus/$target
  mkdir -p "$work"
  local limits=("$@")
  [ -n "$seconds" ] && limits=(-max_total_time="$seconds") && min_runs=0
  echo "fuzz: $target, $workers workers, each ${limits[*]}" >&2
  local start=$SECONDS pids=() w
  for ((w = 1; w <= workers; ++w)); do
    # rss_limit: 2 GiB per input at most (the loaders refuse images over 16384 per side).
    "build-fuzz/tests/fuzz/$target" -seed="$w" "${limits[@]}" -max_len="$max_len" \
      -rss_limit_mb=2560 -artifact_prefix=build-fuzz/artifacts/ -print_final_stats=1 \
      "$work" "tests/fuzz/corpus/${target#fuzz_}" 2>"build-fuzz/$target.$w.log" &
    pids+=($!)
  done
  local runs=0 failed=0 n
  for ((w = 1; w <= workers; ++w)); do
    if ! wait "${pids[w - 1]}"; then
      failed=1
      tail -n 60 "build-fuzz/$target.$w.log" >&2
    fi
    n=$(awk '/stat::number_of_executed_units/ {print $2}' "build-fuzz/$target.$w.log")
    runs=$((runs + ${n:-0}))
  done
  echo "fuzz: $target: $runs inputs in $((SECONDS - start)) s, $(ls "$work" | wc -l) in build-fuzz/corpus/$target" >&2
  if [ "$failed" = 1 ]; then
    status=1
  elif [ "$runs" -lt "$min_runs" ]; then
    echo "fuzz: $target ran $runs inputs, fewer than the $min_runs required" >&2
    status=1
  fi
}
# The project loader is bounded by executions (3 x 10^5 in all), with a time cap as a safety net;
# the image readers by time.
run fuzz_project 8192 "$project_runs" -runs=$(((project_runs + workers - 1) / workers)) -max_total_time=900
run fuzz_image 4096 0 -max_total_time="$image_seconds"
# The Mitsuba and pbrt scene readers (glint convert), by time like the image readers.
run fuzz_scene_exchange 8192 0 -max_total_time="${GLINT_FUZZ_EXCHANGE_SECONDS:-30}"
[ $status -eq 0 ] && echo "fuzz: no crashes" >&2
exit $status
