#!/usr/bin/env bash
# Installs the library into a scratch prefix and builds tests/consumer against it twice, by
# find_package(roving) and by pkg-config, without the project's build tree; both must print the
# same USiAD as `roving measure` on the bunny and its 800-triangle decimation.
set -euo pipefail
cd "$(dirname "$0")/.."
prefix="$(mktemp -d)"
trap 'rm -rf "$prefix"' EXIT
cmake --install build --prefix "$prefix" >/dev/null
cmake -S tests/consumer -B "$prefix/consumer-build" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" >/dev/null
cmake --build "$prefix/consumer-build" >/dev/null
pc_folder="$(dirname "$(find "$prefix" -name roving.pc)")"
g++ -std=c++17 tests/consumer/main.cpp -o "$prefix/consumer-pc" \
  $(PKG_CONFIG_PATH="$pc_folder" pkg-config --cflags --libs roving) -Wl,-rpath,"$pc_folder/.."
./build/datasets_gen/roving-datasets --data "${ROVING_DATA:-../shared/data}" --out "$prefix/data" --quick 2>/dev/null
ref="$prefix/data/bunny.ply"
test="$prefix/data/bunny-800.ply"
expected=$(./build/roving/roving measure "$ref" "$test" --json - | /usr/bin/python3 -c \
  'import json, sys; j = json.load(sys.stdin); print("USiAD %.9g over %d samples" % (j["statistics"]["usiad"], j["samples"]["count"]))')
for consumer in "$prefix/consumer-build/consumer" "$prefix/consumer-pc"; do
  got=$("$consumer" "$ref" "$test")
  if [ "$got" != "$expected" ]; then
    echo "test-install: $consumer printed '$got', expected '$expected'" >&2
    exit 1
  fi
done
echo "test-install: find_package and pkg-config consumers agree with roving measure: $expected"
