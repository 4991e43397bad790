#!/usr/bin/env bash
# Builds the Debian package build-deb/roving_<version>_amd64.deb: the CLI, libroving, its headers,
# CMake and pkg-config files and the Python module, for prefix /usr (no tests, no benchmarks).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh package
source scripts/compiler-cache.sh
cmake -S . -B build-deb -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr \
  -DROVING_BUILD_TESTS=OFF -DROVING_BUILD_BENCHMARKS=OFF "${cache_options[@]}" >/dev/null
cmake --build build-deb --parallel "$(nproc)"
# CPack's shlibs step warns (a "dev" warning) that the Python module has no soname: a Python
# extension never has one, and only libroving belongs in the shlibs file; the warning is dropped.
(cd build-deb && cpack -G DEB 2>&1 >/dev/null | awk '/^CMake Warning \(dev\)/{skip=1} skip&&/^This warning is for project developers/{skip=0; next} !skip' >&2)
ls build-deb/roving_*_amd64.deb
