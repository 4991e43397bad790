#!/usr/bin/env bash
# Issue 49's checks on a lent GPU machine, in one call: it has NVIDIA's driver but none of Debian's
# packages, so it runs what scripts/gpu-bundle.sh packed here (.gpu/) with glvnd's loaders (.gl/,
# as the device tool's README fetches them). In order, each step with its own time limit and log
# under $OUT, none stopping the next:
#   info      nvidia-smi, the EGL vendor files
#   datasets  the scaling pairs (10 M triangles) beside the GL tests on EGL (every GL test binary,
#             ROVING_GL_BACKEND=egl; OSMesa is not carried, so its cases skip, each saying why)
#   timings   bench/gl_timings.py --backends egl --large --huge --whole-views into $OUT/gpu.md
#             (written after each pair): exact roving drawn and computed beside Embree at 1 M, 10 M
#             and 50 M samples, the cooperative method on the bunny pairs (also with its views
#             drawn whole: nothing per view on the CPU)
# about 5 minutes in all on an H100 machine; `gpu-run.sh tests` reruns the tests alone, `gpu-run.sh
# timings` the data sets and the timings alone.
set -uo pipefail
cd "$(dirname "$0")/.."
out=${OUT:-gpu-logs}
mkdir -p "$out"
if [ ! -d .gpu/lib ]; then  # carried anew each call: .gpu holds the bundle alone
  for f in .gl/*.deb; do dpkg -x "$f" /; done
  ldconfig
  tar -xJf .gpu/bundle.tar.xz -C .gpu && mkdir -p build && cp -r .gpu/build/. build/ && touch build/roving/roving
fi
# Debian's libraries for our binaries alone: python3 there keeps the machine's own.
libs=$PWD/.gpu/lib
export ROVING_DATA=$PWD/data
printf '#!/bin/sh\nLD_LIBRARY_PATH=%s exec %s "$@"\n' "$libs" "$PWD/build/roving/roving" >.gpu/roving
chmod +x .gpu/roving
nvidia_egl=/usr/local/nvidia/share/glvnd/egl_vendor.d/10_nvidia.json
if [ -f "$nvidia_egl" ] && ! ls /usr/share/glvnd/egl_vendor.d/*nvidia* >/dev/null 2>&1; then
  export __EGL_VENDOR_LIBRARY_FILENAMES=$nvidia_egl
fi
# The test binaries hold this checkout's paths as they were built here.
[ -e /work/main ] || { mkdir -p /work && ln -s "$PWD" /work/main; }

step() {  # name, seconds, command...
  local name=$1 limit=$2
  shift 2
  echo "== $name (limit ${limit} s) at ${SECONDS} s"
  timeout "$limit" "$@" >"$out/$name.log" 2>&1
  echo "   $name: exit $? at ${SECONDS} s; last lines:"
  tail -n 8 "$out/$name.log" | sed 's/^/     /'
}
gl_tests() {  # backend: every GL test binary at once, 4 at a time; a summary line per binary
  ls build/tests/*_test | xargs -P 4 -I{} sh -c \
    "LD_LIBRARY_PATH=$libs ROVING_GL_BACKEND=$1 {} --gtest_brief=1 >$out/tests-$1-\$(basename {}).log 2>&1; echo \"\$(basename {}) exit \$?: \$(grep -E '^\[  (PASSED|FAILED|SKIPPED)' $out/tests-$1-\$(basename {}).log | tr '\n' ' ')\""
}

if [ "${1:-}" = tests ]; then
  step "tests-${2:-egl}" 240 bash -c "$(declare -f gl_tests); out=$out libs=$libs; gl_tests ${2:-egl}"
  exit 0
fi
if [ "${1:-}" != timings ]; then
  step info 20 bash -c "nvidia-smi; ls -l /usr/share/glvnd/egl_vendor.d /usr/local/nvidia/share/glvnd/egl_vendor.d; \
  echo EGL vendor files: \${__EGL_VENDOR_LIBRARY_FILENAMES:-default}; nproc; python3 -c 'import numpy, pandas; print(numpy.__version__, pandas.__version__)'"
fi
step datasets 120 bash -c "for only in --quick --scaling; do LD_LIBRARY_PATH=$libs \
  build/datasets_gen/roving-datasets --data data --out build/datasets \$only || exit; done" &
[ "${1:-}" = timings ] || step tests-egl 150 bash -c "$(declare -f gl_tests); out=$out libs=$libs; gl_tests egl"
wait
step timings 400 python3 bench/gl_timings.py --roving .gpu/roving --data build/datasets \
  --backends egl --large --huge --whole-views --out "$out/gpu.md"
echo "done at ${SECONDS} s"
