#!/usr/bin/env bash
# Sets up and builds, then opens the editor on projects/default.glint when a display is present
# ($DISPLAY or $WAYLAND_DISPLAY). Without one it renders the default project headlessly to
# renders/default.png and says how to open the editor. Arguments go to the editor, or with no
# display to `glint render`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
if [[ -n "${DISPLAY:-}" || -n "${WAYLAND_DISPLAY:-}" ]]; then
  exec ./build/glint projects/default.glint "$@"
fi
mkdir -p renders
./build/glint render projects/default.glint -o renders/default.png "$@"
echo "The image is in $(pwd)/renders/default.png"
echo "No display here (neither DISPLAY nor WAYLAND_DISPLAY is set), so the editor did not open."
echo "On a desktop, run: ./build/glint projects/default.glint"
echo "On a server: xvfb-run -a ./build/glint projects/default.glint --screenshot shot.png"
