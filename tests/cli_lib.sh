# Shared by the CLI bad-input tests (cli_bad_input.sh, cli_bad_input_media.sh); sourced, not run. A script
# does `set -u`, then `. "$(dirname "$0")/cli_lib.sh"` with the diffray binary as its own $1, and ends with
# `finish NAME`. This file gives: bin (absolute), tmp (removed on exit), the counters, expect_clean and
# expect_error, the ir functions, and the fixtures both scripts read.
bin="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"  # absolute: one check runs in another folder
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
fails=0
passes=0

# One bad-input run: "$bin" ARGS... must exit with a code in 1..127, print exactly one line on stderr (that
# contains PATTERN, when PATTERN is not empty) and leave nothing matching GLOB in $tmp.
expect_clean() {  # expect_clean LABEL GLOB PATTERN ARGS...
  local label="$1" glob="$2" pattern="$3"; shift 3
  rm -f "$tmp"/$glob
  "$bin" "$@" >"$tmp/stdout" 2>"$tmp/stderr"
  local code=$?
  local lines
  lines=$(wc -l <"$tmp/stderr")
  # (also no staged output, core::OutputFiles's NAME.partPID-N.EXT, whatever the glob)
  if [ "$code" -eq 0 ] || [ "$code" -ge 128 ] || [ "$lines" -ne 1 ] || ls "$tmp"/$glob >/dev/null 2>&1 ||
     ls "$tmp"/*.part[0-9]*-[0-9]* >/dev/null 2>&1 ||
     { [ -n "$pattern" ] && ! grep -qF -- "$pattern" "$tmp/stderr"; }; then
    echo "FAIL: $label: exit=$code, stderr lines=$lines"; sed 's/^/    /' "$tmp/stderr"
    fails=$((fails + 1))
  else
    passes=$((passes + 1))
  fi
}
expect_error() {  # expect_error DESCRIPTION ARGS...
  local what="$1"; shift
  expect_clean "$what" "out.csv*" "" "$@"
}

# The tally, as the test's last command: "NAME: P passed, F failed", and non-zero when anything failed.
finish() {  # finish NAME
  echo "$1: $passes passed, $fails failed"
  [ "$fails" -eq 0 ]
}

# diffray ir on a room file given as text (written to $tmp/room.json): one line, no WAV, JSON or CSV left.
expect_ir_says() {  # expect_ir_says DESCRIPTION PATTERN ROOM_JSON_TEXT [ARGS...]: the line must hold PATTERN
  local what="$1" pattern="$2" text="$3"; shift 3
  printf '%s\n' "$text" >"$tmp/room.json"
  local rays=(--rays 2000)
  case " $* " in *" --rays "*) rays=() ;; esac
  expect_clean "ir: $what" "out.*" "$pattern" ir "$tmp/room.json" -o "$tmp/out.wav" "${rays[@]}" "$@"
}
expect_ir_error() {  # expect_ir_error DESCRIPTION ROOM_JSON_TEXT [ARGS...]
  local what="$1"; shift
  expect_ir_says "$what" "" "$@"
}
# The parts of a valid room (a 4 × 3 × 2.5 m box, one source, one listener), for room texts built from them.
mat='"materials": {"w": {"absorption": 0.3, "scattering": 0.2}}'
box='"geometry": [{"box": {"min": [0,0,0], "max": [4,3,2.5], "materials": {"all": "w"}}}]'
src='"sources": [{"position": [1,1,1]}]'
lis='"listeners": [{"position": [3,2,1.2], "radius_m": 0.2}]'

csv="--csv=$tmp/out.csv"
rooms="$(cd "$(dirname "${BASH_SOURCE[0]}")/../rooms" && pwd)"

# Inputs read by metrics, auralize, spectrogram and door: a text file named .wav, and 32-bit float WAVs
# (format 3, 48 kHz, mono) byte by byte, nan.wav holding 1.0 and NaN, ok.wav 1.0 and 0.5.
printf 'not audio\n' >"$tmp/text.wav"
printf 'RIFF\x2c\x00\x00\x00WAVEfmt \x10\x00\x00\x00\x03\x00\x01\x00\x80\xbb\x00\x00\x00\xee\x02\x00\x04\x00\x20\x00data\x08\x00\x00\x00\x00\x00\x80\x3f\x00\x00\xc0\x7f' >"$tmp/nan.wav"
printf 'RIFF\x2c\x00\x00\x00WAVEfmt \x10\x00\x00\x00\x03\x00\x01\x00\x80\xbb\x00\x00\x00\xee\x02\x00\x04\x00\x20\x00data\x08\x00\x00\x00\x00\x00\x80\x3f\x00\x00\x00\x3f' >"$tmp/ok.wav"

# Room files (shoebox.json with its materials.json) and a WDF profile in a folder of their own, for the runs
# made inside it (no output may replace an input, a non-UTF-8 file name, ir -o "") and for ir and wdf cases.
mkdir -p "$tmp/lib"
cp "$rooms/shoebox.json" "$rooms/materials.json" "$rooms/barrier.json" "$tmp/lib/"
printf 'x,amplitude,phase\n-1e-4,1,0\n1e-4,1,0\n' >"$tmp/lib/p.csv"

# A 16-bit mono 48 kHz FLAC of 64 frames whose STREAMINFO claims FRAMES (< 2^36): a lying header.
flac_claiming() {  # flac_claiming OUT.flac FRAMES
  sox -n -r 48000 -c 1 -b 16 "$1" synth 64s sine 440 2>/dev/null && python3 - "$1" "$2" <<'PY'
import sys
path, claimed = sys.argv[1], int(sys.argv[2])
b = bytearray(open(path, "rb").read())
assert b[:4] == b"fLaC" and b[4] & 0x7f == 0, "STREAMINFO first"
field = int.from_bytes(b[18:26], "big")
field = (field & ~((1 << 36) - 1)) | claimed
b[18:26] = field.to_bytes(8, "big")
open(path, "wb").write(bytes(b))
PY
}
