#!/usr/bin/env bash
# Bad input to the diffray CLI must give exactly one line on stderr, a non-zero exit code and no output
# file (design: never a crash, never a half-written output). This script covers auralize, spectrogram, door,
# signal, --play and render, then checks across commands (outputs checked before any work, a full stdout, a
# non-UTF-8 file name, whole numbers, empty names and list entries); cli_bad_input.sh covers validate, wdf,
# metrics, ir and compare, and cli_lib.sh holds what both share. Usage: cli_bad_input_media.sh PATH/TO/diffray
set -u
. "$(dirname "$0")/cli_lib.sh"

# diffray auralize: bad input gives one line and leaves no WAV (nor a temporary) behind.
expect_auralize_error() {  # expect_auralize_error DESCRIPTION ARGS...
  local what="$1"; shift
  expect_clean "auralize: $what" "wet.*" "" auralize "$@"
}
# ok.wav at 44.1 kHz: the same two samples, another rate.
printf 'RIFF\x2c\x00\x00\x00WAVEfmt \x10\x00\x00\x00\x03\x00\x01\x00\x44\xac\x00\x00\x10\xb1\x02\x00\x04\x00\x20\x00data\x08\x00\x00\x00\x00\x00\x80\x3f\x00\x00\x00\x3f' >"$tmp/ok44.wav"
expect_auralize_error "missing IR file"        --ir "$tmp/none.wav" --in "$tmp/ok.wav" -o "$tmp/wet.wav"
expect_auralize_error "missing input file"     --ir "$tmp/ok.wav" --in "$tmp/none.wav" -o "$tmp/wet.wav"
# A dry FLAC whose header claims 2^36 - 1 frames: the output-size check names the input and the claim.
flac_claiming "$tmp/lie.flac" 68719476735
expect_clean "auralize: a dry header claiming 2^36 - 1 frames" "wet.*" "lie.flac: its header claims 68719476735 frames" \
  auralize --ir "$tmp/ok.wav" --in "$tmp/lie.flac" -o "$tmp/wet.wav"
expect_auralize_error "rate mismatch, --no-resample" --ir "$tmp/ok.wav" --in "$tmp/ok44.wav" -o "$tmp/wet.wav" --no-resample
# Without --no-resample the IR is resampled to the input's rate: one info line, a 44.1 kHz output (and, the
# click convolved with itself peaking above 1, the clipping warning only).
if "$bin" auralize --ir "$tmp/ok.wav" --in "$tmp/ok44.wav" -o "$tmp/wet.wav" >"$tmp/stdout" 2>"$tmp/stderr" &&
   grep -q "resampled the impulse response from 48000 Hz to the input's 44100 Hz" "$tmp/stdout" &&
   grep -q "at 44100 Hz" "$tmp/stdout" && ! grep -v "above full scale" "$tmp/stderr" | grep -q .; then passes=$((passes + 1)); else
  echo "FAIL: auralize: a 48 kHz IR on a 44.1 kHz input was not resampled"; sed 's/^/    /' "$tmp/stdout" "$tmp/stderr"; fails=$((fails + 1)); fi
rm -f "$tmp"/wet.*
# An output above full scale is written (float WAV holds it) with one warning giving its peak; one below is not warned about.
"$bin" auralize --ir "$tmp/ok.wav" --in "$tmp/ok.wav" -o "$tmp/wet.wav" --gain 60 >/dev/null 2>"$tmp/stderr"
code=$?
if [ $code -eq 0 ] && [ -s "$tmp/wet.wav" ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] &&
   grep -q "^diffray: warning: .*wet.wav peaks at +[0-9.]* dBFS, above full scale" "$tmp/stderr"; then
  passes=$((passes + 1)); else echo "FAIL: auralize: no clipping warning (exit=$code)"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
"$bin" auralize --ir "$tmp/ok.wav" --in "$tmp/ok.wav" -o "$tmp/wet.wav" --normalize >/dev/null 2>"$tmp/stderr"
if [ $? -eq 0 ] && ! grep -q "above full scale" "$tmp/stderr"; then
  passes=$((passes + 1)); else echo "FAIL: auralize: a clipping warning at -1 dBFS"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
rm -f "$tmp/wet.wav"
expect_auralize_error "NaN in the input"       --ir "$tmp/ok.wav" --in "$tmp/nan.wav" -o "$tmp/wet.wav"
expect_auralize_error "NaN in the input, normalized" --ir "$tmp/ok.wav" --in "$tmp/nan.wav" -o "$tmp/wet.wav" --normalize
expect_auralize_error "NaN in the IR"          --ir "$tmp/nan.wav" --in "$tmp/ok.wav" -o "$tmp/wet.wav"
expect_auralize_error "output folder missing"  --ir "$tmp/ok.wav" --in "$tmp/ok.wav" -o "$tmp/no/such/dir/wet.wav"
expect_auralize_error "output not a .wav"      --ir "$tmp/ok.wav" --in "$tmp/ok.wav" -o "$tmp/wet.csv"
expect_auralize_error "NaN gain"               --ir "$tmp/ok.wav" --in "$tmp/ok.wav" -o "$tmp/wet.wav" --gain nan
expect_auralize_error "no --in"                --ir "$tmp/ok.wav" -o "$tmp/wet.wav"
# --gain is bounded like door's (±120 dB) when parsing, not after the whole convolution.
expect_clean "auralize: gain 200 dB"       "wet.*" "--gain" auralize --ir "$tmp/ok.wav" --in "$tmp/ok.wav" -o "$tmp/wet.wav" --gain 200
expect_clean "auralize: --decode a mono IR" "wet.*" "ok.wav: has 1 channels: an AmbiX signal" auralize --ir "$tmp/ok.wav" --in "$tmp/ok.wav" -o "$tmp/wet.wav" --decode binaural
expect_clean "auralize: --decode 30:95"   "wet.*" "--decode: \"30:95\"" auralize --ir "$tmp/ok.wav" --in "$tmp/ok.wav" -o "$tmp/wet.wav" --decode 30:95
expect_clean "auralize: --hrtf without --decode binaural" "wet.*" "--hrtf: is for --decode binaural" auralize --ir "$tmp/ok.wav" --in "$tmp/ok.wav" -o "$tmp/wet.wav" --hrtf "$tmp/ok.wav"
expect_clean "auralize: gain -1e9 dB"      "wet.*" "--gain" auralize --ir "$tmp/ok.wav" --in "$tmp/ok.wav" -o "$tmp/wet.wav" --normalize --gain -1e9
expect_clean "auralize: --play, gain 200"  "wet.*" "--gain" auralize --ir "$tmp/ok.wav" --in "$tmp/ok.wav" --play --gain 200
cp "$tmp/ok.wav" "$tmp/dry.wav"
"$bin" auralize --ir "$tmp/ok.wav" --in "$tmp/dry.wav" -o "$tmp/dry.wav" >/dev/null 2>"$tmp/stderr"
code=$?
if [ "$code" -ne 0 ] && [ "$code" -lt 128 ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] && cmp -s "$tmp/ok.wav" "$tmp/dry.wav"; then
  passes=$((passes + 1)); else echo "FAIL: auralize: the output may not overwrite the input (exit=$code)"; fails=$((fails + 1)); fi
# The good path: [1, 0.5] * [1, 0.5] = [1, 1, 0.25], three frames, no temporary left.
if "$bin" auralize --ir "$tmp/ok.wav" --in "$tmp/ok.wav" -o "$tmp/wet.wav" --normalize >/dev/null 2>"$tmp/stderr" &&
   python3 - "$tmp/wet.wav" <<'PY' && [ "$(ls "$tmp"/wet.* | wc -l)" -eq 1 ]; then passes=$((passes + 1)); else
import struct, sys
b = open(sys.argv[1], "rb").read()
i = b.index(b"data")
n = struct.unpack("<I", b[i + 4:i + 8])[0]
y = struct.unpack("<%df" % (n // 4), b[i + 8:i + 8 + n])
p = 10 ** (-1 / 20)  # --normalize: peak at -1 dBFS
assert len(y) == 3 and all(abs(a - e) < 1e-6 for a, e in zip(y, (p, p, p / 4))), y
PY
  echo "FAIL: auralize: good run did not write [1, 1, 0.25] normalized"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi

# diffray spectrogram: bad input gives one line and leaves no PNG (nor a temporary) behind.
expect_spectrogram_error() {  # expect_spectrogram_error DESCRIPTION ARGS...
  local what="$1"; shift
  expect_clean "spectrogram: $what" "spec.*" "" spectrogram "$@"
}
expect_spectrogram_error "missing input file"    "$tmp/none.wav" -o "$tmp/spec.png"
expect_spectrogram_error "text file named .wav"  "$tmp/text.wav" -o "$tmp/spec.png"
expect_spectrogram_error "NaN in the input"      "$tmp/nan.wav" -o "$tmp/spec.png"
expect_spectrogram_error "output folder missing" "$tmp/ok.wav" -o "$tmp/no/such/dir/spec.png"
expect_spectrogram_error "output not a .png"     "$tmp/ok.wav" -o "$tmp/spec.wav"
expect_spectrogram_error "channel past the last" "$tmp/ok.wav" -o "$tmp/spec.png" --channel 2
expect_spectrogram_error "negative channel"      "$tmp/ok.wav" -o "$tmp/spec.png" --channel -1
expect_spectrogram_error "odd window"            "$tmp/ok.wav" -o "$tmp/spec.png" --window 1001
expect_spectrogram_error "window too short"      "$tmp/ok.wav" -o "$tmp/spec.png" --window 4
expect_spectrogram_error "negative hop"          "$tmp/ok.wav" -o "$tmp/spec.png" --hop -3
expect_spectrogram_error "zero dB range"         "$tmp/ok.wav" -o "$tmp/spec.png" --range 0
expect_spectrogram_error "no -o"                 "$tmp/ok.wav"
expect_spectrogram_error "mark without a time"  "$tmp/ok.wav" -o "$tmp/spec.png" --mark :START
expect_spectrogram_error "non-numeric mark"      "$tmp/ok.wav" -o "$tmp/spec.png" --mark soon:END
expect_spectrogram_error "hexadecimal mark"      "$tmp/ok.wav" -o "$tmp/spec.png" --mark 0x1p-2:END
# Memory the machine cannot give (a 2 GB address-space limit, while the sweep needs 4 GB) is one line
# naming the cause, not an internal error. Skipped where the binary cannot start under such a limit
# (AddressSanitizer reserves terabytes of address space).
if prlimit --as=2000000000 "$bin" --version >/dev/null 2>&1; then
  real_bin="$bin" bin=prlimit
  expect_clean "signal: out of memory" "big.*" "out of memory" --as=2000000000 "$real_bin" signal sweep --rate 384000 \
    --duration 2700 -o "$tmp/big.wav"
  bin="$real_bin"
fi
# A title with a newline and a gnuplot command after it: drawn as text, the command not run.
if command -v gnuplot >/dev/null 2>&1; then
  "$bin" spectrogram "$tmp/ok.wav" -o "$tmp/t.png" --title 'a
system("touch '"$tmp"'/pwned2")
set title "b' >/dev/null 2>&1
  if [ -f "$tmp/t.png" ] && [ ! -e "$tmp/pwned2" ]; then passes=$((passes + 1)); else
    echo "FAIL: spectrogram: a --title with a newline ran a gnuplot command"; fails=$((fails + 1)); fi
fi
# The good path (with gnuplot): a PNG, and nothing else left beside it.
if command -v gnuplot >/dev/null 2>&1; then
  python3 - "$tmp/sweep.wav" <<'PY'
import math, struct, sys, wave
fs, T = 16000, 1.0
with wave.open(sys.argv[1], "wb") as w:
    w.setnchannels(2); w.setsampwidth(2); w.setframerate(fs)
    frames = b""
    for n in range(int(fs * T)):
        t = n / fs
        v = int(20000 * math.sin(2 * math.pi * (100 * t + (6000 - 100) * t * t / (2 * T))))
        frames += struct.pack("<hh", v, v // 2)
    w.writeframes(frames)
PY
  rm -f "$tmp"/spec.*
  if "$bin" spectrogram "$tmp/sweep.wav" -o "$tmp/spec.png" --window 512 --channel 2 --mark 0.25:START --mark 0.75 >/dev/null 2>"$tmp/stderr" &&
     [ "$(head -c 8 "$tmp/spec.png" 2>/dev/null | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] &&
     [ "$(ls "$tmp"/spec.* | wc -l)" -eq 1 ]; then passes=$((passes + 1)); else
    echo "FAIL: spectrogram: good run did not write a PNG"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
fi

# diffray door: bad input gives one line before any tracing and leaves no output (WAV, PNG, JSON, CSV).
expect_door_error() {  # expect_door_error DESCRIPTION ARGS...
  local what="$1"; shift
  expect_clean "door: $what" "door.*" "" door "$@"
}
# A 0.3 s dry noise burst at 48 kHz.
python3 -c "
import random, struct, wave
w = wave.open('$tmp/burst.wav', 'wb'); w.setnchannels(1); w.setsampwidth(2); w.setframerate(48000)
random.seed(1); w.writeframes(b''.join(struct.pack('<h', int(8000 * random.uniform(-1, 1))) for _ in range(14400)))"
two="$rooms/two-rooms.json"
expect_door_error "missing room file"      "$tmp/none.json" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.1:0.2
expect_door_error "no --close"             "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav"
expect_door_error "END before START"       "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.2:0.1
expect_door_error "--close not a range"    "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close soon
expect_door_error "--close with NaN"       "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close nan:1
expect_door_error "one step"               "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.1:0.2 --steps 1
expect_door_error "room without a door"    "$rooms/shoebox.json" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.1:0.2
expect_door_error "door without a panel"   "$rooms/doorway.json" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.1:0.2
expect_door_error "no such door"           "$two" --door front --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.1:0.2
expect_door_error "no such listener"       "$two" --listener nobody --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.1:0.2
expect_door_error "missing dry file"       "$two" --in "$tmp/none.wav" -o "$tmp/door.wav" --close 0.1:0.2
expect_door_error "NaN in the dry signal"  "$two" --in "$tmp/nan.wav" -o "$tmp/door.wav" --close 0.1:0.2 --rays 100
expect_door_error "output not a .wav"      "$two" --in "$tmp/burst.wav" -o "$tmp/door.mp3" --close 0.1:0.2
expect_door_error "output folder missing"  "$two" --in "$tmp/burst.wav" -o "$tmp/no/such/door.wav" --close 0.1:0.2
expect_door_error "unknown diffraction"    "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.1:0.2 --diffraction magic
# --play: -o, --play or both; --device and --block only with --play; a bad --block and (with no audio
# device, CI) the device itself refused before the tracing, nothing written.
expect_door_error "neither -o nor --play"   "$two" --in "$tmp/burst.wav" --close 0.1:0.2
expect_door_error "--spectrogram without -o" "$two" --in "$tmp/burst.wav" --close 0.1:0.2 --play --spectrogram "$tmp/door.png"
expect_door_error "--device without --play" "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.1:0.2 --device 0
expect_door_error "--block without --play"  "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.1:0.2 --block 256
expect_door_error "--play, tiny --block"    "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.1:0.2 --play --block 1
expect_door_error "--play, no such device"  "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.1:0.2 --play --device no-such-card-xyz
if "$bin" auralize --list-devices 2>/dev/null | grep -q "no audio output devices"; then
  expect_door_error "--play without an audio device" "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.1:0.2 --play
fi
# The good path: two steps at few rays write the WAV (one channel per listener), the PNG, the JSON and the CSV.
if "$bin" door "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.05:0.2 --steps 2 --rays 3000 >/dev/null 2>"$tmp/stderr" &&
   [ "$(head -c 8 "$tmp/door.png" 2>/dev/null | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] &&
   python3 - "$tmp/door.wav" "$tmp/door.json" "$tmp/door.csv" <<'PY'
import json, struct, sys
b = open(sys.argv[1], "rb").read()
assert b[:4] == b"RIFF" and struct.unpack("<H", b[22:24])[0] == 3, "not a 3-channel WAV"
side = json.load(open(sys.argv[2]))
assert [s["gap_m"] for s in side["steps"]] == [side["door_width_m"], 0.0], side["steps"]
assert len(side["listeners"]) == 3 and len(side["panel"]["transmission_loss_db"]) == 8
rows = open(sys.argv[3]).read().splitlines()
assert len(rows) == 1 + 2 * 3, rows
PY
then passes=$((passes + 1)); else
  echo "FAIL: door: good run did not write the WAV, PNG, JSON and CSV"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
# An output above full scale is written with one warning giving its peak in dBFS; 120 dB less is not warned about.
for gain in 60 -60; do
  "$bin" door "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.05:0.2 --steps 2 --rays 3000 --gain $gain >/dev/null 2>"$tmp/stderr"
  code=$?
  warned=$(grep -c "^diffray: warning: .*door.wav peaks at +[0-9.]* dBFS, above full scale.*lower --gain" "$tmp/stderr")
  if [ $code -eq 0 ] && { { [ $gain -gt 0 ] && [ "$warned" -eq 1 ]; } || { [ $gain -lt 0 ] && ! grep -q "full scale" "$tmp/stderr"; }; }; then
    passes=$((passes + 1)); else echo "FAIL: door --gain $gain: clipping warning wrong (exit=$code)"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
done

# diffray signal: bad options give one line and leave no WAV behind.
expect_signal_error() {  # expect_signal_error DESCRIPTION ARGS...
  local what="$1"; shift
  expect_clean "signal: $what" "sig.*" "" signal "$@"
}
expect_signal_error "unknown kind"          noise -o "$tmp/sig.wav"
expect_signal_error "negative duration"     sweep -o "$tmp/sig.wav" --duration -1
expect_signal_error "zero duration"         clicks -o "$tmp/sig.wav" --duration 0
expect_signal_error "NaN duration"          sweep -o "$tmp/sig.wav" --duration nan
expect_signal_error "from = to"             sweep -o "$tmp/sig.wav" --from 1000 --to 1000
expect_signal_error "from above to"         sweep -o "$tmp/sig.wav" --from 2000 --to 1000
expect_signal_error "to above Nyquist"      sweep -o "$tmp/sig.wav" --rate 22050
expect_signal_error "rate too low"          sweep -o "$tmp/sig.wav" --rate 100 --to 40
expect_signal_error "rate too high"         clicks -o "$tmp/sig.wav" --rate 1000000
expect_signal_error "level above 0 dBFS"    clicks -o "$tmp/sig.wav" --level 3
expect_signal_error "zero interval"         clicks -o "$tmp/sig.wav" --interval 0
expect_signal_error "option of another kind" clicks -o "$tmp/sig.wav" --from 100
expect_signal_error "unwritable path"       sweep -o "$tmp/no/such/dir/sig.wav"
expect_signal_error "output not a .wav"     sweep -o "$tmp/sig.csv"
expect_signal_error "speed out of range"    speech -o "$tmp/sig.wav" --speed 5
expect_signal_error "unknown voice"         speech -o "$tmp/sig.wav" --voice nosuchvoice
# A CSV above 10 MB is announced with its size (wdf's cell table of 3 slits: about 150 MB, 3 s); a small
# one (a grating's line table, 54 kB) is not.
"$bin" wdf slits --count 3 --width 50e-6 --spacing 150e-6 --csv "$tmp/big.csv" >/dev/null 2>"$tmp/stderr"
big_mb=$(( ($(stat -c %s "$tmp/big.csv") + 500000) / 1000000 ))
"$bin" wdf grating --csv "$tmp/small.csv" >/dev/null 2>"$tmp/stderr.small"
if [ "$big_mb" -gt 10 ] && grep -q "note: .*big.csv is $big_mb MB" "$tmp/stderr" && ! grep -q "note:" "$tmp/stderr.small"; then
  passes=$((passes + 1)); else echo "FAIL: a big CSV ($big_mb MB) not announced, or a small one announced"; cat "$tmp/stderr" "$tmp/stderr.small" | sed 's/^/    /'; fails=$((fails + 1)); fi
rm -f "$tmp/big.csv" "$tmp/small.csv"
# A WAV cut short (a copy interrupted): read, with one warning naming the file and what is missing (200000
# bytes kept, less the 58-byte header of a mono float WAV).
"$bin" signal clicks -o "$tmp/whole.wav" --duration 2 >/dev/null 2>&1
head -c 200000 "$tmp/whole.wav" >"$tmp/cut.wav"
if "$bin" metrics "$tmp/cut.wav" >/dev/null 2>"$tmp/stderr" && [ "$(grep -c "warning: .*cut.wav: the file is cut short: its header declares 384000 bytes of samples, it holds 199942" "$tmp/stderr")" -eq 1 ] &&
   "$bin" metrics "$tmp/whole.wav" >/dev/null 2>"$tmp/stderr.whole" && ! grep -q "cut short" "$tmp/stderr.whole"; then
  passes=$((passes + 1)); else echo "FAIL: metrics on a truncated WAV: no warning (or one on the whole file)"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
rm -f "$tmp/whole.wav" "$tmp/cut.wav"
expect_clean "signal: voice vulcan (espeak-ng would fall back to English)" "sig.*" "no voice 'vulcan'" signal speech -o "$tmp/sig.wav" --voice vulcan
for v in en-us en+f3 de gmw/en klingon; do  # languages, a variant, a file, a voice name (espeak-ng's Klingon)
  if "$bin" signal speech -o "$tmp/voice.wav" --voice "$v" --text "one" >/dev/null 2>"$tmp/stderr" && [ -s "$tmp/voice.wav" ]; then
    passes=$((passes + 1)); else echo "FAIL: signal speech --voice $v refused"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
  rm -f "$tmp/voice.wav"
done
expect_signal_error "empty text"            speech -o "$tmp/sig.wav" --text " "
# Beyond one WAV file (4 GiB of float32): refused before the samples are made (5.5 GB here).
expect_clean "signal: 3600 s at 384 kHz" "sig.*" "4 GiB" signal clicks -o "$tmp/sig.wav" --rate 384000 --duration 3600
expect_clean "signal: sweep of 3000 s at 384 kHz" "sig.*" "4 GiB" signal sweep -o "$tmp/sig.wav" --rate 384000 --duration 3000
if "$bin" signal clicks -o "$tmp/sig.wav" --duration 0.5 --interval 0.1 >/dev/null 2>"$tmp/stderr" &&
   [ "$(stat -c %s "$tmp/sig.wav")" -gt 96000 ]; then passes=$((passes + 1)); else
  echo "FAIL: signal: a good click train was not written"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
rm -f "$tmp"/sig.*

# auralize --play / --list-devices: --list-devices always exits 0 (listing none is not an error); a device
# that does not exist is one line and exit 2; with no device at all (CI), --play is one line and exit 2, and
# with -o as well no WAV is written before the error.
if "$bin" auralize --list-devices >"$tmp/devices" 2>"$tmp/stderr" && [ ! -s "$tmp/stderr" ] && [ -s "$tmp/devices" ]; then
  passes=$((passes + 1)); else echo "FAIL: auralize --list-devices (exit!=0 or stderr noise)"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
expect_auralize_error "--device index that does not exist" --ir "$tmp/ok.wav" --in "$tmp/ok.wav" --play --device 9999
expect_auralize_error "--device name that does not exist"  --ir "$tmp/ok.wav" --in "$tmp/ok.wav" --play --device no-such-card-xyz
expect_auralize_error "--device without --play"            --ir "$tmp/ok.wav" --in "$tmp/ok.wav" -o "$tmp/wet.wav" --device 0
expect_auralize_error "neither -o nor --play"              --ir "$tmp/ok.wav" --in "$tmp/ok.wav"
expect_auralize_error "--play with a tiny --block"         --ir "$tmp/ok.wav" --in "$tmp/ok.wav" --play --block 1
# --block is checked before -o is written (with a device, too), and refused without --play, like --device.
expect_clean "auralize: --play -o with a huge --block" "wet.*" "--block" auralize --ir "$tmp/ok.wav" --in "$tmp/ok.wav" --play -o "$tmp/wet.wav" --block 100000
expect_clean "auralize: --block without --play"        "wet.*" "--block" auralize --ir "$tmp/ok.wav" --in "$tmp/ok.wav" -o "$tmp/wet.wav" --block 256
if grep -q "no audio output devices" "$tmp/devices"; then
  expect_auralize_error "--play without an audio device"      --ir "$tmp/ok.wav" --in "$tmp/ok.wav" --play
  expect_auralize_error "--play and -o without an audio device" --ir "$tmp/ok.wav" --in "$tmp/ok.wav" --play -o "$tmp/wet.wav"
  "$bin" auralize --ir "$tmp/ok.wav" --in "$tmp/ok.wav" --play >/dev/null 2>"$tmp/stderr"
  code=$?
  if [ "$code" -eq 2 ] && grep -q "no audio output device" "$tmp/stderr"; then passes=$((passes + 1)); else
    echo "FAIL: auralize --play without a device: exit=$code"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
fi

# diffray render: scene errors and options, one line each and no image left behind.
png="$tmp/out.csv.png"  # out.csv* : caught by expect_error's no-output check (PNG, PFM and JSON)
light='"rectangles": [{"centre": [0,0,0], "normal": [0,0,1], "width_m": 1, "height_m": 1}],
  "camera": {"position": [0,0,1], "look_at": [0,0,0], "fov_deg": 40, "pixels": [8, 8]}'
printf '{%s, "lights": [{"type": "point", "position": [0,0,0.5]}]}\n' "$light" >"$tmp/light.json"
printf '{%s, "lights": [{"type": "laser", "position": [0,0,0.5], "direction": [0,0,-1], "width_m": 0.1}]}\n' "$light" >"$tmp/nowl.json"
printf '{%s, "lights": [{"type": "point", "position": [0,0,0.5]}], "colour": 1}\n' "$light" >"$tmp/key.json"
printf '{%s, "lights": [{"type": "point", "position": [0,0,0.5], "power_w": -1}]}\n' "$light" >"$tmp/neg.json"
printf '{"rectangles": [' >"$tmp/syntax.json"
printf '{%s, "lights": [{"type": "point", "position": [0,0,0.5]}]}\n' "${light/\"look_at\": \[0,0,0\]/\"look_at\": [0,0,0], \"up\": [0,0,1]}" >"$tmp/camup.json"
expect_error "render: missing scene"      render "$tmp/none.json" -o "$png"
expect_error "render: JSON syntax"        render "$tmp/syntax.json" -o "$png"
expect_error "render: laser without nm"   render "$tmp/nowl.json" -o "$png"
expect_error "render: unknown key"        render "$tmp/key.json" -o "$png"
expect_error "render: negative power"     render "$tmp/neg.json" -o "$png"
expect_error "render: zero photons"       render "$tmp/light.json" -o "$png" --photons 0
expect_error "render: photons and spp"    render "$tmp/light.json" -o "$png" --photons 100 --spp 2
expect_error "render: not a PNG"          render "$tmp/light.json" -o "$tmp/out.csv"
expect_error "render: missing folder"     render "$tmp/light.json" -o "$tmp/no/such/dir/out.png"
expect_error "render: zero exposure"      render "$tmp/light.json" -o "$png" --photons 100 --exposure 0
printf '{%s, "lights": [{"type": "point", "position": [-1e308,0,0.5]}]}\n' "$light" >"$tmp/far.json"
expect_clean "render: light at -1e308 m"  "out.csv*" "lights[0].position[0]: must be within" render "$tmp/far.json" -o "$png"
printf '{"rectangles": [{"centre": [0,0,0], "normal": [0,0,1], "width_m": 1e300, "height_m": 1}], "lights": [{"type": "point", "position": [0,0,0.5]}],
  "camera": {"position": [0,0,1], "look_at": [0,0,0], "fov_deg": 40, "pixels": [8, 8]}}\n' >"$tmp/huge.json"
expect_clean "render: 1e300 m wide wall"  "out.csv*" "rectangles[0].width_m: must be at most" render "$tmp/huge.json" -o "$png"
expect_error "render: float format"      render "$tmp/light.json" -o "$png" --photons 100 --float tiff
expect_error "render: CSV folder"         render "$tmp/light.json" -o "$png" --photons 100 --csv "$tmp/no/such/dir/p.csv"
expect_error "render: CSV extension"      render "$tmp/light.json" -o "$png" --photons 100 --csv "$tmp/out.csv.txt"
printf '{%s, "lights": [{"type": "point", "position": [0,0,0.5]}], "occluders": [{"type": "grating", "centre": [0,0,0.2], "normal": [0,0,1], "width_m": 0.1, "height_m": 0.1, "period_m": 1.6e-6, "modulation": 3, "reflectance": 1.5}]}\n' "$light" >"$tmp/refl.json"
expect_error "render: reflectance > 1"    render "$tmp/refl.json" -o "$png"
expect_error "validate image-cd: 900 nm"  validate image-cd --wavelength 900e-9 --rays 1000 "$csv"
area='"type": "area", "centre": [0,0,0.5], "normal": [0,0,-1]'
printf '{%s, "lights": [{%s, "width_m": 0, "height_m": 0.1}]}\n' "$light" "$area" >"$tmp/area0.json"
printf '{%s, "lights": [{%s, "up": [0,0,3], "width_m": 0.1, "height_m": 0.1}]}\n' "$light" "$area" >"$tmp/areaup.json"
printf '{%s, "lights": [{%s, "width_m": 0.1, "height_m": 0.1, "colour": 1}]}\n' "$light" "$area" >"$tmp/areakey.json"
printf '{%s, "lights": [{%s, "width_m": 0.1, "height_m": 0.1, "two_sided": "yes"}]}\n' "$light" "$area" >"$tmp/area2.json"
expect_clean "render: area zero width"    "out.csv*" "lights[0].width_m" render "$tmp/area0.json" -o "$png"
expect_clean "render: area up = normal"   "out.csv*" "lights[0].up" render "$tmp/areaup.json" -o "$png"
expect_clean "render: area unknown key"   "out.csv*" "colour" render "$tmp/areakey.json" -o "$png"
expect_clean "render: area two_sided"     "out.csv*" "lights[0].two_sided" render "$tmp/area2.json" -o "$png"
lens='"type": "lens", "centre": [0,0,0.2], "normal": [0,0,1], "width_m": 0.01, "height_m": 0.01'
printf '{%s, "lights": [{"type": "point", "position": [0,0,0.5]}], "occluders": [{%s, "aperture_width_m": 1e-3, "aperture_height_m": 1e-3, "focal_length_m": 0}]}\n' "$light" "$lens" >"$tmp/f0.json"
printf '{%s, "lights": [{"type": "point", "position": [0,0,0.5]}], "occluders": [{%s, "aperture_width_m": 1e-3, "aperture_height_m": 1e-3, "focal_length_m": -0.5}]}\n' "$light" "$lens" >"$tmp/fneg.json"
printf '{%s, "lights": [{"type": "point", "position": [0,0,0.5]}], "occluders": [{%s, "aperture_width_m": 1e-3, "aperture_height_m": 1e-3}]}\n' "$light" "$lens" >"$tmp/fmissing.json"
printf '{%s, "lights": [{"type": "point", "position": [0,0,0.5]}], "occluders": [{%s, "aperture_width_m": 1e-3, "focal_length_m": 0.5}]}\n' "$light" "$lens" >"$tmp/nob.json"
printf '{%s, "lights": [{"type": "point", "position": [0,0,0.5]}], "occluders": [{%s, "aperture_width_m": 0.02, "aperture_height_m": 1e-3, "focal_length_m": 0.5}]}\n' "$light" "$lens" >"$tmp/wide.json"
expect_clean "render: lens focal 0"        "out.csv*" "focal_length_m: must be > 0"  render "$tmp/f0.json" -o "$png"
expect_clean "render: lens focal < 0"      "out.csv*" "focal_length_m: must be > 0"  render "$tmp/fneg.json" -o "$png"
expect_clean "render: lens without focal"  "out.csv*" "focal_length_m"               render "$tmp/fmissing.json" -o "$png"
expect_clean "render: lens without height" "out.csv*" "aperture_height_m"            render "$tmp/nob.json" -o "$png"
expect_clean "render: lens wider than plate" "out.csv*" "aperture_width_m"           render "$tmp/wide.json" -o "$png"
expect_error "validate image-lens-psf: even pixels" validate image-lens-psf --pixels 60 --rays 1000 "$csv"
expect_error "validate image-lens-psf: infrared"    validate image-lens-psf --wavelength 1e-6 --rays 1000 "$csv"
expect_error "validate image-lens-psf: strong lens" validate image-lens-psf --focal 1e-3 --rays 1000 "$csv"
# Every output is checked before the render: a folder where a file goes (CSV, sidecar), and --spp past the
# photon cap (computed in double: 1e13 × 64 pixels would wrap a uint64), a negative --seed.
mkdir -p "$tmp/d.csv" "$tmp/side.json"
expect_error "render: CSV is a folder"    render "$tmp/light.json" -o "$png" --photons 100 --csv "$tmp/d.csv"
expect_clean "render: sidecar is a folder" "side.p*" "side.json: is a folder" render "$tmp/light.json" -o "$tmp/side.png" --photons 100
expect_clean "render: --spp over the cap" "out.csv*" "over the limit of 1e13" render "$tmp/light.json" -o "$png" --spp 1e13
expect_clean "render: negative seed"      "out.csv*" "--seed"  render "$tmp/light.json" -o "$png" --photons 100 --seed -3
expect_clean "render: camera up"          "out.csv*" "camup.json: camera.up: must" render "$tmp/camup.json" -o "$png" --photons 100
expect_clean "validate: CSV is a folder"  "out.csv*" "is a folder" validate slit-fraunhofer --rays 1000 --csv "$tmp/d.csv"
expect_clean "validate: negative seed"    "out.csv*" "--seed" validate slit-fraunhofer --rays 1000 --seed -1 "$csv"
expect_ir_error "negative seed" "{$mat, $box, $src, $lis}" --seed -2
mkdir -p "$tmp/out.json"
expect_clean "ir: sidecar is a folder" "out.[wc]*" "out.json: is a folder" ir "$tmp/room.json" -o "$tmp/out.wav" --rays 2000
rmdir "$tmp/out.json"

# The good path writes the PNG (by its signature), the PFM and the sidecar.
"$bin" render "$tmp/light.json" -o "$tmp/good.png" --photons 2000 >/dev/null 2>&1
if [ "$(head -c 8 "$tmp/good.png" 2>/dev/null | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ] &&
   [ "$(head -c 2 "$tmp/good.pfm" 2>/dev/null)" = "PF" ] && grep -q '"photons": 2000' "$tmp/good.json" 2>/dev/null; then
  passes=$((passes + 1)); else echo "FAIL: render did not write PNG, PFM and JSON"; fails=$((fails + 1)); fi

expect_error "no subcommand"
expect_error "unknown subcommand"     frobnicate

# Values no range check catches: NaN for ir's length, a room volume of 1e-300 m³ (it hung), a WAV whose
# header claims a 1 GHz sample rate (4 kB that took 3 GB before failing).
expect_clean "ir --length nan" "nanlen.*" "--length" ir "$tmp/lib/shoebox.json" -o "$tmp/nanlen.wav" --length nan --rays 1000
expect_error "decay-metrics --volume 1e-300" validate decay-metrics --volume 1e-300 "$csv"
python3 - "$tmp/rate.wav" <<'PY'
import struct, sys
n, sr = 1000, 1000000000
data = struct.pack('<%df' % n, *([0.0] * n))
fmt = struct.pack('<IHHIIHH', 16, 3, 1, sr, sr * 4, 4, 32)
open(sys.argv[1], 'wb').write(b'RIFF' + struct.pack('<I', 36 + len(data)) + b'WAVE' + b'fmt ' + fmt + b'data' +
                              struct.pack('<I', len(data)) + data)
PY
expect_clean "metrics: a 1 GHz sample rate" "rate.json" "sample rate" metrics "$tmp/rate.wav"

# Results that cannot be written to stdout (a full disk) are an error, not a silent success.
if [ -w /dev/full ]; then
  "$bin" validate slit-fraunhofer --rays 2000 --json >/dev/full 2>"$tmp/stderr"
  code=$?
  if [ "$code" -ne 0 ] && [ "$code" -lt 128 ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ]; then passes=$((passes + 1)); else
    echo "FAIL: --json to a full stdout exited $code"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
fi
# A file name that is not UTF-8 (legal on Linux) is reported in JSON, not an internal error after the work.
cp "$tmp/lib/shoebox.json" "$tmp/lib/$(printf 'b\377d.json')"
(cd "$tmp/lib" && "$bin" ir "$(printf 'b\377d.json')" -o "$(printf 'o\377.wav')" --rays 2000 --json >/dev/null 2>"$tmp/stderr")
code=$?
if [ "$code" -eq 0 ] && [ -s "$tmp/lib/$(printf 'o\377.json')" ]; then passes=$((passes + 1)); else
  echo "FAIL: ir with a non-UTF-8 file name exited $code"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
# The sidecar keeps its bands in frequency order (an ordered JSON object), 63 Hz before 1000 Hz.
if python3 - "$tmp/lib/$(printf 'o\377.json')" <<'PY'
import json, sys
side = json.load(open(sys.argv[1], 'rb'), object_pairs_hook=lambda pairs: pairs)
listeners = dict(side)["listeners"]
bands = [k for k, _ in dict(listeners[0])["bands"]]
sys.exit(0 if bands and [float(b) for b in bands] == sorted(float(b) for b in bands) else 1)
PY
then passes=$((passes + 1)); else echo "FAIL: the ir sidecar's bands are not in frequency order"; fails=$((fails + 1)); fi

# The good path writes the CSV completely (header + one row per bin).
"$bin" validate slit-fraunhofer --rays 20000 --bins 11 --csv "$tmp/good.csv" >/dev/null 2>&1
if [ "$(wc -l <"$tmp/good.csv" 2>/dev/null)" = "12" ]; then passes=$((passes + 1)); else
  echo "FAIL: good run did not write 12 CSV lines"; fails=$((fails + 1)); fi

# With gnuplot present, --plot writes a PNG (checked by its signature).
if command -v gnuplot >/dev/null 2>&1; then
  "$bin" validate slit-fraunhofer --rays 20000 --bins 11 --plot "$tmp/p.png" >/dev/null 2>&1
  if [ "$(head -c 8 "$tmp/p.png" 2>/dev/null | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]; then
    passes=$((passes + 1)); else echo "FAIL: --plot did not write a PNG"; fails=$((fails + 1)); fi
fi

# Values once taken silently (clamped, truncated, dropped, read as octal) or blamed on the wrong option or file.
expect_clean "--seed above 2^64-1"     "out.csv*" "--seed: must be at most 18446744073709551615" validate slit-fraunhofer --rays 1000 --seed 99999999999999999999999 "$csv"
expect_clean "validate --order 2.5"    "out.csv*" "--order: must be a whole number" validate shoebox-ism --order 2.5 --rays 1000 "$csv"
expect_clean "validate --floor 0.7"    "out.csv*" "--floor: must be a whole number" validate door-room --floor 0.7 --rays 1000 "$csv"
expect_clean "ir --ism-order 2.5"      "out.*" "--ism-order: must be a whole number" ir "$rooms/shoebox.json" -o "$tmp/out.wav" --rays 1000 --ism-order 2.5
expect_clean "ir --threads 1e-400"     "out.*" "--threads: must be a whole number" ir "$rooms/shoebox.json" -o "$tmp/out.wav" --rays 1000 --threads 1e-400
printf 'not a SOFA file\n' >"$tmp/bad.sofa"
expect_clean "door --hrtf not SOFA"     "door.*" "bad.sofa: not a SOFA file" door "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.1:0.2 --format binaural --hrtf "$tmp/bad.sofa"
expect_clean "door --hrtf without binaural" "door.*" "--hrtf: is for --format binaural" door "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.1:0.2 --hrtf "$tmp/bad.sofa"
expect_clean "door --steps 2.5"        "door.*" "--steps: must be a whole number" door "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.1:0.2 --steps 2.5
expect_clean "wdf --count 2.5"         "out.csv*" "--count: must be a whole number" wdf slits --count 2.5 "$csv"
expect_clean "wdf --count 0x3"         "out.csv*" "--count: must be a whole number" wdf slits --count 0x3 "$csv"
expect_clean "--threads 1.5"           "out.csv*" "--threads: must be a whole number" validate slit-fraunhofer --rays 1000 --threads 1.5 "$csv"
expect_clean "signal --rate 48000.5"   "sig.*" "--rate: must be a whole number" signal clicks -o "$tmp/sig.wav" --rate 48000.5
# Numbers are decimal: strtod and CLI11 read 0x10 as 16. Empty input names are refused by name.
expect_clean "ir --rays 0x10"          "out.*" "--rays: must be a whole number" ir "$rooms/shoebox.json" -o "$tmp/out.wav" --rays 0x10
expect_clean "render --photons 0x10"   "out.*" "--photons: must be a whole number" render "$rooms/light/double-slit.json" -o "$tmp/out.png" --photons 0x10
expect_clean "door --close 0x1:2"      "door.*" "--close: must be START:END" door "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0x1:2
expect_clean "auralize --gain 0x10"    "wet.*" "--gain: must be a decimal number" auralize --ir "$tmp/ok.wav" --in "$tmp/ok.wav" -o "$tmp/wet.wav" --gain 0x10
expect_clean "wdf --wavelength 0x1p-21" "out.csv*" "--wavelength: must be a decimal number" wdf slit --wavelength 0x1p-21 "$csv"
expect_clean "metrics \"\""             "out.*" "file: an input file name must not be empty" metrics ""
expect_clean "auralize --ir \"\""       "wet.*" "--ir: an input file name must not be empty" auralize --ir "" --in "$tmp/ok.wav" -o "$tmp/wet.wav"
expect_clean "ir \"\""                  "out.*" "room: an input file name must not be empty" ir "" -o "$tmp/out.wav"
# A whole number may be written as 1e1 (like --rays 2e6), and a leading zero is decimal: --seed 010 is seed 10.
"$bin" validate slit-fraunhofer --rays 2000 --seed 010 --csv "$tmp/s010.csv" >/dev/null 2>&1
"$bin" validate slit-fraunhofer --rays 2000 --seed 10 --csv "$tmp/s10.csv" >/dev/null 2>&1
if cmp -s "$tmp/s010.csv" "$tmp/s10.csv" && "$bin" signal clicks -o "$tmp/sig.wav" --rate 4.8e4 --duration 0.1 >/dev/null 2>&1 &&
   "$bin" validate shoebox-ism --order 2e0 --rays 1000 --json >/dev/null 2>&1; then passes=$((passes + 1)); else
  echo "FAIL: --seed 010 is not seed 10, or --rate 4.8e4 / --order 2e0 was refused"; fails=$((fails + 1)); fi
rm -f "$tmp"/s010.csv "$tmp"/s10.csv "$tmp"/sig.*
# An empty output name is refused, naming the option, not taken as "no such output" or the default name.
for args in "validate slit-fraunhofer --rays 1000 --csv" "validate slit-fraunhofer --rays 1000 --plot" "wdf slit --csv" \
            "compare $rooms/barrier.json --models utd --fine-per-octave 2 --csv" "ir $rooms/shoebox.json --rays 1000 --plot" \
            "render $tmp/light.json --photons 100 -o" "auralize --ir $tmp/ok.wav --in $tmp/ok.wav -o" "signal clicks -o" \
            "spectrogram $tmp/ok.wav -o" "door $two --in $tmp/burst.wav --close 0.1:0.2 -o"; do
  # shellcheck disable=SC2086
  expect_clean "empty output name: ${args%% *} ${args##* }" "out.*" "an output file name must not be empty" $args ""
done
expect_clean "door --spectrogram \"\"" "door.*" "--spectrogram: an output file name must not be empty" door "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.1:0.2 --spectrogram ""
(cd "$tmp" && "$bin" ir lib/shoebox.json -o "" --rays 1000 >/dev/null 2>"$tmp/stderr")
if [ $? -eq 2 ] && grep -q -- "--output: an output file name must not be empty" "$tmp/stderr" && ! ls "$tmp"/shoebox.* >/dev/null 2>&1; then
  passes=$((passes + 1)); else echo "FAIL: ir -o \"\" was not refused"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
expect_clean "--freq 125,,250"         "out.csv*" 'empty entry in "125,,250"' validate door-rs --freq 125,,250 --rays 1000 "$csv"
expect_clean "--freq 125,"             "out.csv*" 'empty entry in "125,"' validate door-rs --freq 125, --rays 1000 "$csv"
expect_clean "--dims 10,,7,3"          "out.csv*" "--dims: empty entry" validate shoebox-ism --dims 10,,7,3 --rays 1000 "$csv"
python3 - "$tmp" <<'EOF'
import json, struct, sys
def wav(name, samples, rate):
    data = struct.pack('<%df' % len(samples), *samples)
    fmt = struct.pack('<IHHIIHH', 16, 3, 1, rate, rate * 4, 4, 32)
    open(f"{sys.argv[1]}/{name}", 'wb').write(b'RIFF' + struct.pack('<I', 36 + len(data)) + b'WAVE' + b'fmt ' + fmt +
                                              b'data' + struct.pack('<I', len(data)) + data)
wav('fs100.wav', [0.0] * 50 + [1.0] + [0.0] * 349, 100)
wav('huge.wav', [3e38] * 4, 48000)  # finite, but its convolution with itself overflows float
room = {"materials": {"w": {"absorption": 0.3, "scattering": 0.2}},
        "geometry": [{"box": {"min": [0, 0, 0], "max": [4, 3, 2.5], "materials": {"all": "w"}}}],
        "sources": [{"position": [1, 1, 1]}], "output": {"max_length_s": 600},
        "listeners": [{"position": [3, 0.2 + 0.1 * i, 1.2], "radius_m": 0.05} for i in range(25)]}
json.dump(room, open(f"{sys.argv[1]}/many.json", "w"))
EOF
expect_clean "spectrogram of a 100 Hz file" "spec.*" "fs100.wav: sample rate 100 Hz" spectrogram "$tmp/fs100.wav" -o "$tmp/spec.png" --window 8
expect_clean "door --close 0:1e300"    "door.*" "--close: START and END must be at most" door "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0:1e300
expect_clean "pilot past the histogram limit" "out.*" "many.json: output.max_length_s: with no IR length set" ir "$tmp/many.json" -o "$tmp/out.wav" --rays 1000
expect_clean "auralize --normalize overflow" "wet.*" "/wet.wav: refusing to write" auralize --ir "$tmp/huge.wav" --in "$tmp/huge.wav" -o "$tmp/wet.wav" --normalize
expect_clean "auralize: resampling 480x" "wet.*" "ok.wav: cannot resample its 48000 Hz to the input's 100 Hz" auralize --ir "$tmp/ok.wav" --in "$tmp/fs100.wav" -o "$tmp/wet.wav"
expect_clean "door: a 100 Hz dry signal" "door.*" "fs100.wav: sample rate 100 Hz: the room's IRs" door "$two" --in "$tmp/fs100.wav" -o "$tmp/door.wav" --close 0.1:0.2
# wdf: an option of another kind is refused, not ignored.
expect_clean "wdf slit --count 8"      "out.csv*" "--count: applies to slits only, not slit" wdf slit --count 8 "$csv"
expect_clean "wdf slit --modulation 3" "out.csv*" "--modulation: applies to grating only" wdf slit --modulation 3 "$csv"
expect_clean "wdf profile --u-range"   "out.csv*" "--u-range: applies to" wdf profile --profile "$tmp/lib/p.csv" --u-range 5 "$csv"

# A mistyped command: one line naming the nearest commands (or none), before CLI11's "a subcommand is required".
expect_clean "command: near miss" "out.csv*" "diffray irr: no such command; did you mean ir?" irr x
expect_clean "command: far from any" "out.csv*" "diffray xyzzy: no such command (see diffray --help)" xyzzy
# --threads above the cores: a note, and the run goes on with the cores (the sidecar says how many).
"$bin" ir "$rooms/shoebox.json" --threads 100000 --rays 500 -o "$tmp/threads.wav" >/dev/null 2>"$tmp/stderr"
if [ $? -eq 0 ] && grep -q "^diffray: note: --threads 100000 is more than the [0-9]* cores here: using [0-9]*$" "$tmp/stderr" &&
   python3 -c "import json,os,sys; sys.exit(0 if json.load(open(sys.argv[1]))['threads'] == len(os.sched_getaffinity(0)) else 1)" "$tmp/threads.json"; then
  passes=$((passes + 1)); else echo "FAIL: --threads above the cores"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi

finish cli_bad_input_media
