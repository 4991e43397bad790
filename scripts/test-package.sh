#!/usr/bin/env bash
# Builds the Debian package and checks it as a user of a fresh Debian 12 machine meets it: in a
# clean Debian 12 tree (debootstrap, minbase, under build-deb/debian12) with nothing else installed,
# `apt install ./roving_*.deb` resolves its dependencies from Debian's archive; then from an empty
# folder there: `roving` on PATH, docs/library.md's C++ program built by find_package(roving) with no
# environment variable, `import roving` in Debian's python3 and the Python tests against it. As root
# (debootstrap, chroot).
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/step.sh
source_dir="$PWD"
bash scripts/setup.sh package
step "building the Debian package (scripts/package.sh)" sh -c 'bash scripts/package.sh >/dev/null'
deb="$(ls "$PWD"/build-deb/roving_*_amd64.deb)"
echo "test-package: $(basename "$deb"), $(du -h "$deb" | cut -f1); Depends: $(dpkg-deb -f "$deb" Depends)"
unexpected=$(dpkg-deb -c "$deb" | awk '{print $6}' | grep -v -E '^\./(usr/?|usr/(bin|lib|include|share)/.*|usr/lib/python3/dist-packages/.*)$' || true)
[ -z "$unexpected" ] || { echo "test-package: unexpected paths in the package: $unexpected" >&2; exit 1; }

# A clean Debian 12, from the archive this machine uses; kept between runs (build-deb/ is ignored).
root="$PWD/build-deb/debian12"
mirror=$(sed -n 's/^URIs: *\(http[^ ]*\/debian\)$/\1/p' /etc/apt/sources.list.d/debian.sources 2>/dev/null | head -n 1)
if [ ! -x "$root/usr/bin/apt-get" ]; then
  rm -rf "$root"
  step "a clean Debian 12 tree (debootstrap --variant=minbase)" \
    debootstrap --variant=minbase bookworm "$root" "${mirror:-http://deb.debian.org/debian}" >/dev/null
fi
in_root() { chroot "$root" env -i PATH=/usr/sbin:/usr/bin:/sbin:/bin HOME=/root DEBIAN_FRONTEND=noninteractive "$@"; }
cp "$deb" "$root/tmp/"
rm -rf "$root/tmp/app" && mkdir -p "$root/tmp/app"
/usr/bin/python3 scripts/docs_blocks.py docs/library.md cpp > "$root/tmp/app/main.cpp"
/usr/bin/python3 scripts/docs_blocks.py docs/library.md cmake > "$root/tmp/app/CMakeLists.txt"
cp data/fandisk.obj "$root/tmp/app/"
step "apt-get install ./$(basename "$deb") in the clean tree (and g++, cmake for a consumer)" in_root sh -c \
  "apt-get update -qq && apt-get install -y -qq --no-install-recommends /tmp/$(basename "$deb") g++ cmake ninja-build >/dev/null"
in_root sh -c 'cd /tmp && [ "$(command -v roving)" = /usr/bin/roving ] && roving --version'
# A GL method: OSMesa is opened at run time, so only the package's own Depends can bring it.
in_root sh -c 'cd /tmp/app && roving measure fandisk.obj fandisk.obj --method roving --samples area:2000 --quiet > gl.txt && grep "^method" gl.txt'
in_root sh -c 'cd /tmp/app && cmake -S . -B build -G Ninja >/dev/null && cmake --build build >/dev/null && ./build/app fandisk.obj fandisk.obj'
in_root sh -c 'cd /tmp && python3 -c "import roving; print(\"import roving:\", roving.__file__, \"methods:\", \", \".join(roving.methods))"'
# The Python tests against the installed module and CLI, with pytest and NumPy from Debian (the parts
# needing Open3D or matplotlib are left to the main suite, where setup.sh installs them).
rm -rf "$root/tmp/src" && mkdir -p "$root/tmp/src/tests" "$root/tmp/src/python" "$root/tmp/src/docs"
cp -r tests/python tests/ibsm tests/data "$root/tmp/src/tests/" && cp -r data "$root/tmp/src/" && cp python/roving.pyi "$root/tmp/src/python/"
cp docs/python.md "$root/tmp/src/docs/"
step "the Python tests on the installed module (python3-pytest, python3-numpy)" in_root sh -c \
  "apt-get install -y -qq --no-install-recommends python3-pytest python3-numpy >/dev/null && cd /tmp && \
   PYTHONDONTWRITEBYTECODE=1 ROVING_CLI=/usr/bin/roving ROVING_SOURCE_DIR=/tmp/src python3 -m pytest -q -p no:cacheprovider /tmp/src/tests/python"
test -f "$root/usr/lib/python3/dist-packages/roving.pyi" || { echo "test-package: roving.pyi is not installed beside the module" >&2; exit 1; }
in_root apt-get remove -y -qq roving >/dev/null
echo "test-package: in a clean Debian 12 tree, apt installs the package; roving on PATH (a GL method included), find_package(roving) and import roving work"
