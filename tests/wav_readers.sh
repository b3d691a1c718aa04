#!/usr/bin/env bash
# Every kind of WAV diffray writes (signal: sweep, clicks, speech; ir, omni, AmbiX and binaural; auralize, plain and --normalize; door, omni and binaural),
# read by sox (soxi) and by libsndfile (diffray metrics): both must see the same channels and frames, sox
# must print no warning, and libsndfile's reader must say nothing about the file.
# The one exception, for files of more than two channels only: sox 14.4.2 (Debian 12) prints "wave header
# missing extended part of fmt chunk" on every WAVE_FORMAT_EXTENSIBLE file of a non-PCM sub-format, because
# after the 22 bytes of the extensible part its reader looks for a second cbSize that the format does not
# have. That header is the one the WAVE spec requires above two channels; audio_wav_test checks it byte by
# byte. For those files that exact line, and nothing else, is accepted.
# Usage: wav_readers.sh DIFFRAY ROOMS_DIR
set -u
bin="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"  # absolute: the checks run in $tmp
rooms="$(cd "$2" && pwd)"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
passes=0
fails=0
fail() { echo "FAIL: $*"; fails=$((fails + 1)); }

if ! command -v soxi >/dev/null; then
  echo "soxi not found: apt-get install sox (tools/deps.sh lists it)"; exit 1
fi
cp "$rooms/shoebox.json" "$rooms/two-rooms.json" "$rooms/two-rooms.obj" "$rooms/materials.json" "$tmp/"
cd "$tmp" || exit 1

run() {  # run ARGS...: a diffray command that must succeed
  if ! "$bin" "$@" >run.out 2>run.err; then fail "diffray $*"; sed 's/^/    /' run.err; fi
}

check() {  # check FILE CHANNELS
  local f="$1" channels="$2"
  [ -f "$f" ] || { fail "$f was not written"; return; }
  local sox_c sox_s
  sox_c=$(soxi -c "$f" 2>sox.err)
  sox_s=$(soxi -s "$f" 2>>sox.err)
  local allowed="soxi WARN wav: wave header missing extended part of fmt chunk"
  local unexpected
  if [ "$channels" -gt 2 ]; then unexpected=$(grep -vxF "$allowed" sox.err); else unexpected=$(cat sox.err); fi
  [ -z "$unexpected" ] || fail "$f: sox says: $unexpected"
  [ "$sox_c" = "$channels" ] || fail "$f: sox reads $sox_c channels, expected $channels"
  if ! "$bin" metrics "$f" >lsf.out 2>lsf.err; then fail "$f: libsndfile (diffray metrics) refuses it"; sed 's/^/    /' lsf.err; return; fi
  [ -s lsf.err ] && fail "$f: diffray metrics warns: $(cat lsf.err)"
  local head
  head=$(head -1 lsf.out)
  case "$head" in
    *": $sox_s frames at "*", channel 1 of $channels") passes=$((passes + 1)) ;;
    *) fail "$f: libsndfile reads '$head', sox $sox_s frames of $sox_c channels" ;;
  esac
}

run signal sweep -o sweep.wav --duration 0.5
check sweep.wav 1
run signal clicks -o clicks.wav --duration 0.3
check clicks.wav 1
run signal speech -o speech.wav --text "one"
check speech.wav 1
run ir shoebox.json --rays 2000  # two listeners
check shoebox.ir.wav 2
run ir two-rooms.json --rays 2000 -o three.wav  # three listeners
check three.wav 3
run ir shoebox.json --rays 2000 -o amb.wav --format ambix --order 2  # an AmbiX file per listener
check amb.R1.ambix.wav 9
check amb.R2.ambix.wav 9
run ir shoebox.json --rays 2000 -o bin.wav --format binaural  # a two-ear file per listener (Debian's KEMAR set)
check bin.R1.binaural.wav 2
run auralize --ir shoebox.ir.wav --in clicks.wav -o wet.wav
check wet.wav 2
run auralize --ir three.wav --in clicks.wav -o wet3.wav --normalize
check wet3.wav 3
run door two-rooms.json --in clicks.wav -o door.wav --close 0.05:0.15 --steps 2 --rays 2000
check door.wav 3
run door two-rooms.json --in clicks.wav -o door1.wav --close 0.05:0.15 --steps 2 --rays 2000 --listener A
check door1.wav 1
run door two-rooms.json --in clicks.wav -o doorb.wav --close 0.05:0.15 --steps 2 --rays 2000 --listener B-hidden --format binaural
check doorb.wav 2

echo "wav_readers: $passes passed, $fails failed"
[ "$fails" -eq 0 ]
