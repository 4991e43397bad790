#!/usr/bin/env bash
# Installs the library into a scratch prefix, as docs/library.md says for a prefix of one's own, and
# runs that page's snippets as written: the C++ program built by find_package(roving) and by
# pkg-config (both must print the USiAD `roving measure` prints on the bunny and its 800-triangle
# decimation), the Python example, and help(roving.measure) naming every argument.
set -euo pipefail
cd "$(dirname "$0")/.."
prefix="$(mktemp -d)"
trap 'rm -rf "$prefix"' EXIT
cmake --install build --prefix "$prefix" >/dev/null
libdir="$prefix/lib"  # GNUInstallDirs: lib/<multiarch> only for prefix /usr
pydir="$(echo "$prefix"/lib/python3*/dist-packages)"
[ -z "$(find "$prefix/include" -mindepth 1 -maxdepth 1 ! -name roving)" ] ||
  { echo "test-install: headers outside include/roving/: $(ls "$prefix/include")" >&2; exit 1; }

app="$prefix/app"
mkdir -p "$app"
/usr/bin/python3 scripts/docs_blocks.py docs/library.md cpp > "$app/main.cpp"
/usr/bin/python3 scripts/docs_blocks.py docs/library.md cmake > "$app/CMakeLists.txt"
(cd "$app" && CMAKE_PREFIX_PATH="$prefix" cmake -S . -B build -G Ninja >/dev/null && cmake --build build >/dev/null)
(cd "$app" && PKG_CONFIG_PATH="$libdir/pkgconfig" &&
  g++ -std=c++17 main.cpp -o app-pc $(PKG_CONFIG_PATH="$libdir/pkgconfig" pkg-config --cflags --libs roving))

./build/datasets_gen/roving-datasets --out "$prefix/data" --quick 2>/dev/null
ref="$prefix/data/bunny.ply"
test="$prefix/data/bunny-800.ply"
expected=$(./build/roving/roving measure "$ref" "$test" --json - | /usr/bin/python3 -c \
  'import json, sys; j = json.load(sys.stdin); print("USiAD %.9g over %d samples" % (j["statistics"]["usiad"], j["samples"]["count"]))')
for consumer in "$app/build/app" "$app/app-pc"; do
  got=$(LD_LIBRARY_PATH="$libdir" "$consumer" "$ref" "$test")
  if [ "$got" != "$expected" ]; then
    echo "test-install: $consumer printed '$got', expected '$expected'" >&2
    exit 1
  fi
done
echo "test-install: docs/library.md's program, by find_package and by pkg-config, agrees with roving measure: $expected"

# The Python example as written, from the checkout's root, with the installed module first on the path.
PYTHONPATH="$pydir" /usr/bin/python3 -c "$(/usr/bin/python3 scripts/docs_blocks.py docs/library.md python)" >/dev/null
# From elsewhere, with the installed module only; help() documents both functions.
(cd "$prefix" && PYTHONPATH="$pydir" /usr/bin/python3 - <<'PY'
import roving
assert roving.__file__.startswith(__import__("os").environ["PYTHONPATH"]), roving.__file__
for function, words in ((roving.measure, ("reference, test:", "per_sample", "Example:")),
                        (roving.batch, ("out=", "Example:"))):
    missing = [w for w in words if w not in function.__doc__]
    assert not missing, f"{function.__name__}: help() does not say {missing}"
print("test-install: the Python example runs as written; help() documents measure and batch")
PY
)
# In the checkout's root with nothing set, `import roving` finds the C++ source folder roving/ first:
# its __init__.py must hand over to build/python, never leave an empty namespace package.
env -u PYTHONPATH /usr/bin/python3 -c 'import roving; assert roving.__file__.endswith(".so") and callable(roving.measure), roving.__file__'
echo "test-install: import roving from the checkout's root gets the built module"
