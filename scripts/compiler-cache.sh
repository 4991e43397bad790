# Sourced by build.sh, package.sh and test-sanitizers.sh: `cmake ... "${cache_options[@]}"` compiles through ccache
# where it is installed, keyed on paths relative to the checkout (CCACHE_BASEDIR), so that the
# Debian package's build (build-deb/: the same sources and flags) takes build/'s objects instead of
# compiling them a second time.
cache_options=()
if command -v ccache >/dev/null; then
  export CCACHE_BASEDIR="$PWD" CCACHE_NOHASHDIR=1
  cache_options=(-DCMAKE_C_COMPILER_LAUNCHER=ccache -DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
fi
