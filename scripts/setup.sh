#!/usr/bin/env bash
# Installs what Glint needs to build, run and test on Debian 12 / Ubuntu 22.04+.
# Only missing packages are installed; re-running is cheap. Needs root or sudo.
set -euo pipefail

packages=(
  cmake ninja-build pkg-config g++ python3
  libglfw3-dev libglm-dev libstb-dev libepoxy-dev
  nlohmann-json3-dev libtinyexr-dev libgtest-dev
  libgl1-mesa-dri libegl-mesa0 libglx-mesa0 libegl1
  xvfb xauth
  clang   # libFuzzer targets and the sanitizer preset (scripts/fuzz.sh, CMakePresets.json)
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done

if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  "${sudo_cmd[@]}" apt-get update
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
fi

# cargo fetches the pinned tinyfiledialogs and Dear ImGui crates at configure time
# (cmake/TinyFileDialogs.cmake, cmake/DearImGui.cmake).
if ! command -v cargo >/dev/null 2>&1 && [ ! -x "$HOME/.cargo/bin/cargo" ]; then
  echo "setup: cargo not found; installing Debian's cargo" >&2
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y --no-install-recommends cargo
fi
# libFuzzer and the sanitizer runtimes: a package of their own from LLVM 14 on Debian 12
# (libclang-rt-N-dev); older Ubuntu ships them inside clang's libclang-common-N-dev.
clang_major=$(clang --version | sed -n 's/.*clang version \([0-9]*\).*/\1/p' | head -n1)
rt="libclang-rt-${clang_major}-dev"
if apt-cache show "$rt" >/dev/null 2>&1 &&
   ! dpkg-query -W -f='${Status}' "$rt" 2>/dev/null | grep -q "install ok installed"; then
  echo "setup: installing $rt" >&2
  sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "$rt"
fi
echo "setup: all dependencies present" >&2
