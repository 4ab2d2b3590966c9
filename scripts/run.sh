#!/usr/bin/env bash
# Sets up, builds, and renders the default project to renders/default.png.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
mkdir -p renders
./build/glint render projects/default.glint -o renders/default.png "$@"
echo "The image is in $(pwd)/renders/default.png"
