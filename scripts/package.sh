#!/usr/bin/env bash
# Builds the Debian package build-deb/roving_<version>_amd64.deb: the CLI, libroving, its headers,
# CMake and pkg-config files and the Python module, for prefix /usr (no tests, no benchmarks).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh package
cmake -S . -B build-deb -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_INSTALL_PREFIX=/usr \
  -DROVING_BUILD_TESTS=OFF -DROVING_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build build-deb --parallel "$(nproc)"
(cd build-deb && cpack -G DEB >/dev/null)
ls build-deb/roving_*_amd64.deb
