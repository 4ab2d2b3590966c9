#!/usr/bin/env bash
# A first render with each entry point of the path tracer, under a time limit, before the test
# suites: a driver on which the trace shader does not finish (Mesa 25's llvmpipe never left a
# loop of an earlier shader) then fails here in minutes with a message that says so, instead of
# every GL test running into its own timeout.
#   bash scripts/smoke_render.sh [GLINT] [SECONDS]
set -uo pipefail
cd "$(dirname "$0")/.."
glint="${1:-./build/glint}"
limit="${2:-120}"
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for backend in fragment compute; do
  timeout "$limit" "$glint" render projects/default.glint -o "$out/smoke.png" --width 16 --spp 4 \
    --backend "$backend" >"$out/log" 2>&1
  rc=$?
  if [ "$rc" -eq 124 ]; then
    echo "smoke_render: glint render --backend $backend of projects/default.glint (16 px, 4 spp) did not finish in $limit s: the trace shader hangs on this OpenGL driver" >&2
    grep -m1 "OpenGL" "$out/log" >&2
    exit 1
  elif [ "$rc" -ne 0 ]; then
    echo "smoke_render: glint render --backend $backend of projects/default.glint failed (exit $rc):" >&2
    cat "$out/log" >&2
    exit 1
  fi
done
echo "smoke_render: both entry points rendered" >&2
