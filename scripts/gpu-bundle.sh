#!/usr/bin/env bash
# Packs what a GPU machine without Debian's packages needs to run the GL checks (issue 49) into
# .gpu/ (ignored): the built roving, roving-datasets and GL test binaries in build/'s layout, the
# shared libraries they load that are not the C library's or the GL vendor's (libEGL comes from
# the machine's driver through glvnd), packed with xz. Not OSMesa: with its LLVM, Z3 and ICU it is
# 180 MB (45 MB packed), past what a call carries beside the checkout, so llvmpipe's figures stay
# those of results/gpu-cameras.md. scripts/gpu-run.sh runs there on it.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/build.sh
rm -rf .gpu && mkdir -p .gpu/build/roving .gpu/build/datasets_gen .gpu/build/tests .gpu/lib
cp build/roving/roving .gpu/build/roving/
cp build/datasets_gen/roving-datasets .gpu/build/datasets_gen/
gl_tests=(gl_methods_test exactness_test gl_colour_test representations_test cli_test cli_report_test)
for t in "${gl_tests[@]}"; do cp "build/tests/$t" .gpu/build/tests/; done
# Every library the binaries load, less glibc's and GL's own dispatch libraries.
for f in .gpu/build/*/*; do ldd "$f"; done | awk '/=> \// {print $3}' | sort -u |
  grep -Ev '/(libc|libm|libdl|librt|libpthread|ld-linux-x86-64|libEGL|libGL|libGLX|libGLdispatch|libOpenGL)\.so' |
  while read -r lib; do cp -L "$lib" .gpu/lib/; done
strip --strip-unneeded .gpu/build/*/* .gpu/lib/* 2>/dev/null || true
tar -C .gpu -cJf .gpu/bundle.tar.xz build lib
rm -rf .gpu/build .gpu/lib
ls -l .gpu/bundle.tar.xz
