#!/usr/bin/env bash
# Installs diffray's build dependencies from Debian 12 packages when any is missing, and builds (the normal
# build in build/, the sanitizer build in build-sanitize/). Sourced by the scripts of tools/. As root it runs
# apt-get; otherwise it prints the exact command to run and stops.
DIFFRAY_PACKAGES=(build-essential cmake pkg-config libembree-dev libtbb-dev libfftw3-dev libeigen3-dev
  libsndfile1-dev portaudio19-dev libcerf-dev nlohmann-json3-dev libcli11-dev googletest libgtest-dev libbenchmark-dev gnuplot-nox)
DIFFRAY_PACKAGES+=(libsamplerate0-dev espeak-ng)  # resampling in auralize, speech in `diffray signal`
DIFFRAY_PACKAGES+=(libpng-dev)  # PNG output of rendered images
DIFFRAY_PACKAGES+=(libopenexr-dev)  # OpenEXR (float) output of rendered images
DIFFRAY_PACKAGES+=(libmysofa-dev)  # SOFA HRTFs for binaural IRs; libmysofa1 ships the MIT KEMAR set
DIFFRAY_PACKAGES+=(sox)  # tests/wav_readers.sh: sox reads every WAV diffray writes
DIFFRAY_PACKAGES+=(netcdf-bin)  # ncgen: the SOFA test fixtures (tests/spatial_sofa_test.cpp) written from CDL text
DIFFRAY_PACKAGES+=(python3-dev python3-pybind11 python3-numpy python3-pytest)  # the Python module (src/python)
# Only the sanitizer build (tools/sanitize, tools/fuzz) adds these: clang with its sanitizer runtimes
# (AddressSanitizer, UBSan, libFuzzer).
DIFFRAY_SANITIZE_PACKAGES=(clang libclang-rt-dev)

diffray_install_deps() {
  local missing=()
  for p in "${DIFFRAY_PACKAGES[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  local cmd="apt-get install -y --no-install-recommends ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then
    echo "diffray needs these Debian packages: ${missing[*]}" >&2
    echo "run as root:  apt-get update && $cmd" >&2
    exit 1
  fi
  echo "installing: ${missing[*]}" >&2
  export DEBIAN_FRONTEND=noninteractive
  apt-get update -qq && apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

diffray_build() {
  cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build build -j"$(nproc)"
}

# The sanitizer build, build-sanitize/: clang, ASan + UBSan (float-to-integer overflow included, any report
# fatal) and the libFuzzer harnesses (DIFFRAY_FUZZ). The library is compiled once, for the harnesses
# (tools/fuzz) and for the sanitized CLI and tests (tools/sanitize). No Python module: a sanitized extension
# needs the runtime preloaded into python3.
diffray_sanitize_build() {  # diffray_sanitize_build TARGET...    (DIFFRAY_JOBS sets the parallelism)
  local flags="-fsanitize=address,undefined,float-cast-overflow -fno-sanitize-recover=all"
  flags+=" -fno-omit-frame-pointer -gline-tables-only"
  local launcher=()
  command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++ "${launcher[@]}" \
    -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="-fsanitize=address,undefined" \
    -DCMAKE_SHARED_LINKER_FLAGS="-fsanitize=address,undefined" -DDIFFRAY_FUZZ=ON -DDIFFRAY_PYTHON=OFF >/dev/null
  cmake --build build-sanitize -j"${DIFFRAY_JOBS:-$(nproc)}" --target "$@"
}
