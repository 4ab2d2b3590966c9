#!/usr/bin/env bash
# The benchmark: speed against error for the bench scenes, and Mitsuba 3 as an independent
# reference. Makes its own Python environment (bench/.venv, pinned by bench/requirements.txt),
# builds Glint when build/glint is missing (and no --glint is given), then runs bench/tools/run.py, which writes
# bench/reports/RESULTS.md and its plots. Arguments go to run.py (--quick: tiny validation run written
# to build-bench/quick/; --help lists the rest), or with --caustics first to caustic_race.py.
set -euo pipefail
cd "$(dirname "$0")/.."
VENV=bench/.venv
PY=${PYTHON:-python3}
if [ ! -x "$VENV/bin/python" ]; then
  "$PY" -m venv "$VENV" || {
    echo "bench: '$PY -m venv' failed (on Debian: apt-get install python3-venv)" >&2; exit 1; }
fi
if ! cmp -s bench/requirements.txt "$VENV/.requirements-installed"; then
  "$VENV/bin/python" -m pip install --quiet --disable-pip-version-check -r bench/requirements.txt
  cp bench/requirements.txt "$VENV/.requirements-installed"
fi
# Build only when the default binary is used and missing (`--glint PATH` names another).
case " $* " in
  *" --glint "*|*" --glint="*) ;;
  *) [ -x build/glint ] || bash scripts/build.sh ;;
esac
export PYTHONDONTWRITEBYTECODE=1
# --caustics (first): the race on the caustic scenes alone, bench/tools/caustic_race.py, which
# writes bench/reports/CAUSTICS.md and leaves RESULTS.md as it is.
if [ "${1:-}" = "--caustics" ]; then
  shift
  exec "$VENV/bin/python" bench/tools/caustic_race.py "$@"
fi
exec "$VENV/bin/python" bench/tools/run.py "$@"
