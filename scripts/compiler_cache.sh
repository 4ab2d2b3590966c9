# Sourced by build.sh, test.sh and fuzz.sh: compile through ccache (installed by setup.sh), so
# that a rebuild, the sanitizer build and the fuzz build of unchanged sources (and a fresh
# checkout of the same sources, wherever it lies) reuse earlier compiles. CMake reads the
# launcher from the environment when it first configures a build folder. Paths are hashed
# relative to the checkout (CCACHE_BASEDIR, CCACHE_NOHASHDIR), so another clone hits too; the
# price is that an object taken from the cache keeps the compile directory of the checkout that
# first compiled it in its debug information. GLINT_NO_CCACHE=1 turns it off.
if [ "${GLINT_NO_CCACHE:-0}" != 1 ] && command -v ccache >/dev/null 2>&1; then
  export CMAKE_C_COMPILER_LAUNCHER=ccache CMAKE_CXX_COMPILER_LAUNCHER=ccache
  export CCACHE_BASEDIR="${CCACHE_BASEDIR:-$(pwd)}" CCACHE_NOHASHDIR=1
fi
