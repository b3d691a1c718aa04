#!/usr/bin/env bash
# Installs the built diffray into a temporary prefix and builds tests/install/consumer against the installed
# tree only, four ways: CMake (find_package) with diffray::diffray (libdiffray.so) and
# diffray::diffray_static (libdiffray.a), pkg-config with libdiffray.so and with libdiffray.a; each program
# must run and print the T30s of rooms/shoebox.json. Usage: consumer_test.sh BUILD_DIR SOURCE_DIR. Everything lives in a temporary folder
# removed on exit.
set -euo pipefail
build=$(cd "$1" && pwd)
src=$(cd "$2" && pwd)
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
prefix="$tmp/prefix"
scene="$src/rooms/shoebox.json"
consumer="$src/tests/install/consumer"

cmake --install "$build" --prefix "$prefix" >"$tmp/install.log"
for f in bin/diffray include/diffray/diffray.h; do
  [ -e "$prefix/$f" ] || { echo "FAIL: $f not installed"; exit 1; }
done
libdir=$(dirname "$(find "$prefix" -name libdiffray.a | head -1)")
[ -e "$libdir/libdiffray.so" ] || { echo "FAIL: no libdiffray.so beside libdiffray.a"; exit 1; }

run() {  # run LABEL PROGRAM: it must succeed and print a finite T30 at 1 kHz
  local label="$1"; shift
  if ! "$@" "$scene" >"$tmp/$label.out" 2>&1 || ! grep -Eq '^T30 1000 Hz: [0-9]' "$tmp/$label.out"; then
    echo "FAIL: $label"; sed 's/^/    /' "$tmp/$label.out"; exit 1
  fi
  echo "$label: $(grep '^T30 1000' "$tmp/$label.out")"
}

# 1. CMake: find_package(diffray CONFIG) from the prefix, and nothing else (diffray::diffray and
# diffray::diffray_static).
cmake -S "$consumer" -B "$tmp/cmake" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_BUILD_TYPE=Release >"$tmp/cmake.log" ||
  { cat "$tmp/cmake.log"; exit 1; }
cmake --build "$tmp/cmake" >>"$tmp/cmake.log" || { cat "$tmp/cmake.log"; exit 1; }
run cmake "$tmp/cmake/consumer"
run cmake-static "$tmp/cmake/consumer_static"

# 2. pkg-config: compile once, link with the shared library, then statically with libdiffray.a.
export PKG_CONFIG_PATH="$libdir/pkgconfig"
c++ -std=c++17 -O2 $(pkg-config --cflags diffray) -c "$consumer/main.cpp" -o "$tmp/main.o"
c++ "$tmp/main.o" -o "$tmp/consumer_pc" $(pkg-config --libs diffray) -Wl,-rpath,"$libdir"
run pkg-config "$tmp/consumer_pc"
# The archive with the system's shared libraries: pkg-config --static would also name the private
# dependencies of sndfile.pc (-lmp3lame, …), whose static or development files Debian 12 does not install,
# so the archive's dependencies are asked for by module (Requires.private) plus Libs.private (Embree).
# --as-needed: the archive, named first, resolves every diffray symbol, so -ldiffray records no dependency
# on libdiffray.so.
c++ "$tmp/main.o" -o "$tmp/consumer_static" "$libdir/libdiffray.a" -Wl,--as-needed \
  $(pkg-config --libs diffray $(pkg-config --print-requires-private diffray)) -lembree3
if readelf -d "$tmp/consumer_static" | grep -q 'libdiffray'; then
  echo "FAIL: the static consumer depends on libdiffray.so"; exit 1
fi
run pkg-config-static "$tmp/consumer_static"
echo "install_consumer: ok"
