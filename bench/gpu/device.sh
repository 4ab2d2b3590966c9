#!/usr/bin/env bash
# Runs the GPU bench on the GPU machine, from the repository's root there, with what
# bench/gpu/prepare.sh put into .gpu and .gl (bench/gpu/README.md). Writes bench/reports/GPU.md and
# copies it, with the renders' logs, to $OUT when that is set. Arguments go to gpu_bench.py.
# `--local` first: a check on the machine that prepared it (no packages unpacked over /, no
# wheels installed; bench/.venv's Python), e.g. `bash bench/gpu/device.sh --local --dry`.
set -uo pipefail
cd "$(dirname "$0")/../.."
LOCAL=0
[ "${1:-}" = "--local" ] && { LOCAL=1; shift; }
PY=python3
if [ "$LOCAL" = 1 ]; then
  [ -x bench/.venv/bin/python ] && PY=bench/.venv/bin/python
else
  for f in .gl/*.deb; do dpkg -x "$f" /; done
  ldconfig
fi
if [ -z "$(ls /usr/share/glvnd/egl_vendor.d/ 2>/dev/null)" ] && \
   [ -f /usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json ]; then
  export __EGL_VENDOR_LIBRARY_FILENAMES=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
fi
if [ "$LOCAL" = 0 ] && ls .gpu/whl/*.whl >/dev/null 2>&1; then
  python3 -m pip install -q --no-index --no-deps --no-compile --no-cache-dir --upgrade \
    --target /tmp/site .gpu/whl/*.whl && export PYTHONPATH=/tmp/site
fi
export LD_LIBRARY_PATH=$PWD/.gpu/lib${LD_LIBRARY_PATH:+:$LD_LIBRARY_PATH}
export PYTHONUNBUFFERED=1
nvidia-smi --query-gpu=name,driver_version --format=csv,noheader || true
"$PY" bench/gpu/gpu_bench.py --glint .gpu/glint "$@" 2>&1 | tee /tmp/gpu_bench.log
rc=${PIPESTATUS[0]}
if [ -n "${OUT:-}" ]; then
  cp bench/reports/GPU.md "$OUT/" 2>/dev/null
  cp /tmp/gpu_bench.log "$OUT/"
fi
exit "$rc"
