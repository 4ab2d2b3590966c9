#!/usr/bin/env bash
# Prepares, on this machine, what bench/gpu/device.sh needs on a GPU machine that has no
# internet (bench/gpu/README.md): .gpu/glint (stripped) and the shared libraries it needs that a
# CUDA image lacks (.gpu/lib), Mitsuba and Dr.Jit wheels for the GPU machine's Python
# (.gpu/whl, Mitsuba cut down to the rgb variants so that everything fits the 64 MiB a device
# call carries), and the GL loader packages (.gl/*.deb: libEGL and friends of glvnd, which
# dispatch to the NVIDIA driver there). Both folders are git-ignored.
#   bash bench/gpu/prepare.sh [--no-mitsuba]
set -euo pipefail
cd "$(dirname "$0")/../.."
MITSUBA=1
[ "${1:-}" = "--no-mitsuba" ] && MITSUBA=0
if [ ! -x build/glint ]; then
  cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo >/dev/null
  cmake --build build --target glint
fi
rm -rf .gpu
mkdir -p .gpu/lib .gpu/whl .gl
strip --strip-all -o .gpu/glint build/glint
# Everything glint links except the C and C++ runtimes, which the GPU machine's own system has
# (a newer one: an older copy first on the library path could break its Python).
ldd build/glint | awk '/=> \//{print $1" "$3}' | while read -r name path; do
  case "$name" in
    libc.so*|libm.so*|libdl.so*|libpthread.so*|librt.so*|ld-linux*|libstdc++.so*|libgcc_s.so*|libz.so*) ;;
    *) cp -L "$path" ".gpu/lib/$name" ;;
  esac
done
# GL loaders (as the device tool's notes say): unpacked over / there, before glint starts.
o='-oAPT::Architecture=amd64 -oAPT::Architectures=amd64 -oDir::State::Lists=/tmp/amd64'
mkdir -p /tmp/amd64/partial
if ! ls .gl/*.deb >/dev/null 2>&1; then
  apt-get $o update >/dev/null
  (cd .gl && apt-get $o download libvulkan1 libegl1 libglvnd0 libopengl0 libgl1 libglx0 libgles2)
fi
if [ "$MITSUBA" = 1 ]; then
  tmp=$(mktemp -d)
  python3 -m pip download -q --no-deps --only-binary=:all: --python-version 3.12 --implementation cp \
    --platform manylinux_2_28_x86_64 --platform manylinux_2_27_x86_64 --platform manylinux_2_17_x86_64 \
    --platform manylinux2014_x86_64 -d "$tmp" \
    "$(grep '^mitsuba==' bench/requirements.txt)" "$(grep '^drjit==' bench/requirements.txt)"
  cp "$tmp"/drjit-*.whl .gpu/whl/
  python3 bench/gpu/slim_wheel.py "$tmp"/mitsuba-*.whl .gpu/whl/
  rm -rf "$tmp"
fi
du -sh .gpu .gl
echo "prepared: carry [\".gl\", \".gpu\"] and run: bash bench/gpu/device.sh"
