#!/usr/bin/env bash
# Installs what Glint needs to build, run and test on Debian 12 / Ubuntu 22.04+.
# Only missing packages are installed; re-running is cheap. Needs root or sudo.
set -euo pipefail

packages=(
  cmake ninja-build pkg-config g++ python3
  ccache   # scripts/compiler_cache.sh: rebuilds and the sanitizer and fuzz builds reuse compiles
  libglfw3-dev libglm-dev libstb-dev libepoxy-dev
  nlohmann-json3-dev libtinyexr-dev libgtest-dev
  libgl1-mesa-dri libegl-mesa0 libglx-mesa0 libegl1
  xvfb xauth
  python3-pip   # pip download of the denoiser's wheel (below)
  clang   # libFuzzer targets and the sanitizer preset (scripts/fuzz.sh, CMakePresets.json)
  slurmctld slurmd slurm-client munge   # the farm test's one-node cluster (tests/farm)
  dpkg-dev file desktop-file-utils   # the .deb (CPack: dpkg-shlibdeps, file) and its tests (tests/install)
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

# Mesa's llvmpipe, the CPU OpenGL driver that the tests and machines without a GPU run: Debian
# 12's own Mesa 22.3 traces Glint's shaders at 0.36-0.71x the speed of Mesa 25 (bench/reports/
# THROUGHPUT.md, "Mesa 25"), which Debian ships for Debian 12 in bookworm-backports. On
# Debian 12 setup takes Mesa from there, the version it was measured and tested with.
mesa_pin="25.0.7-2~bpo12+1"
mesa_packages=(libgl1-mesa-dri libegl-mesa0 libglx-mesa0 libgbm1 mesa-libgallium)
install_backports_mesa() {
  local sudo_cmd=()
  [ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
  if ! grep -rqs 'bookworm-backports' /etc/apt/sources.list /etc/apt/sources.list.d/; then
    echo "setup: adding Debian's bookworm-backports (for Mesa 25)" >&2
    printf '%s\n' 'Types: deb' 'URIs: http://deb.debian.org/debian' 'Suites: bookworm-backports' \
      'Components: main' 'Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg' |
      "${sudo_cmd[@]}" tee /etc/apt/sources.list.d/bookworm-backports.sources >/dev/null || return 1
  fi
  "${sudo_cmd[@]}" apt-get update || return 1
  echo "setup: installing Mesa $mesa_pin from bookworm-backports" >&2
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y --no-install-recommends \
    -t bookworm-backports "${mesa_packages[@]/%/=$mesa_pin}" && return 0
  # Backports keeps only its newest version: take that one, and say so.
  echo "setup: WARNING: Mesa $mesa_pin is no longer in bookworm-backports; installing its current Mesa" >&2
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y --no-install-recommends \
    -t bookworm-backports "${mesa_packages[@]}"
}
mesa_version=$(dpkg-query -W -f='${Version}' libgl1-mesa-dri 2>/dev/null || echo 0)
if grep -qx 'VERSION_CODENAME=bookworm' /etc/os-release 2>/dev/null &&
   ! dpkg --compare-versions "$mesa_version" ge 25; then
  # Glint works on Debian 12's own Mesa too, only slower: a machine that cannot reach
  # backports keeps it.
  install_backports_mesa ||
    echo "setup: WARNING: could not install Mesa 25 from bookworm-backports; staying on Mesa $mesa_version (Glint works there, at 0.36-0.71x the speed on the CPU)" >&2
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
# Intel Open Image Denoise (glint render --denoise, the editor's Denoise toggle): no registry
# ships it for C/C++, so its own prebuilt libraries come from PyPI's pyoidn wheel, pinned by
# hash (cmake/oidn-requirements.txt), into a cache outside the source tree and the build; CMake
# extracts the libraries next to glint (cmake/OpenImageDenoise.cmake). x86_64 Linux only: the
# wheel holds nothing else, and glint then says that denoising is unavailable.
if [ "$(uname -s)" = Linux ] && [ "$(uname -m)" = x86_64 ]; then
  oidn_cache="${GLINT_DEPS_CACHE:-${XDG_CACHE_HOME:-$HOME/.cache}/glint-deps}"
  wheel="$oidn_cache/pyoidn-2.5.1.0-py3-none-manylinux2014_x86_64.whl"
  if [ ! -f "$wheel" ]; then
    echo "setup: downloading the pinned pyoidn wheel (Open Image Denoise 2.5.1, 88 MB) into $oidn_cache" >&2
    mkdir -p "$oidn_cache"
    python3 -m pip download --no-deps --require-hashes --only-binary=:all: \
      --platform manylinux2014_x86_64 --python-version 3.8 --implementation py \
      -r "$(dirname "$0")/../cmake/oidn-requirements.txt" -d "$oidn_cache"
  fi
else
  echo "setup: Open Image Denoise ships for x86_64 Linux only: glint builds without denoising here" >&2
fi
echo "setup: all dependencies present" >&2
