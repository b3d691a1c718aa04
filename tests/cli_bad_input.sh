#!/usr/bin/env bash
# Bad input to the diffray CLI must give exactly one line on stderr, a non-zero exit code and no output
# file (design: never a crash, never a half-written output). Usage: cli_bad_input.sh PATH/TO/diffray
set -u
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

csv="--csv=$tmp/out.csv"
expect_error "zero-width slit"        validate slit-fraunhofer --width 0 --rays 1000 "$csv"
expect_error "negative width"         validate double-slit --width -1e-4 --rays 1000 "$csv"
expect_error "zero wavelength"        validate slit-fresnel --wavelength 0 --rays 1000 "$csv"
expect_error "NaN width"              validate slit-fraunhofer --width nan --rays 1000 "$csv"
expect_error "distance 1e30 m (beyond float)" validate slit-fraunhofer --distance 1e30 --rays 1000 "$csv"
expect_error "half-plane source at 1e30 m"    validate half-plane --source-distance 1e30 --rays 1000 "$csv"
expect_error "door-rs at 900 kHz"     validate door-rs --freq 9e5 --rays 1000 "$csv"
expect_error "infinite distance"      validate slit-fraunhofer --distance inf --rays 1000 "$csv"
expect_error "negative frequency"     validate door-rs --freq 125,-250 --rays 1000 "$csv"
expect_error "spacing below width"    validate double-slit --width 1e-4 --spacing 5e-5 --rays 1000 "$csv"
expect_error "unknown case"           validate no-such-case "$csv"
expect_error "image: spacing below width" validate image-double-slit --width 1e-4 --spacing 5e-5 --rays 1000 "$csv"
expect_error "image: infrared"       validate image-double-slit --wavelength 1e-6 --rays 1000 "$csv"
expect_error "unknown option"         validate slit-fraunhofer --no-such-option 3 "$csv"
expect_error "option of another case" validate slit-fraunhofer --spacing 1e-4 --rays 1000 "$csv"
expect_error "non-numeric value"      validate slit-fraunhofer --width wide --rays 1000 "$csv"
expect_error "too few bins"           validate slit-fraunhofer --bins 2 --rays 1000 "$csv"
expect_error "zero rays"              validate slit-fraunhofer --rays 0 "$csv"
expect_error "unknown sampler"        validate slit-fraunhofer --sampler magic "$csv"
expect_error "unwritable CSV"         validate grating-orders --rays 20000 --csv "$tmp/no/such/dir/out.csv"
expect_error "unwritable plot"         validate grating-orders --rays 20000 --plot "$tmp/no/such/dir/out.png"
expect_error "zero-width wdf slit"    wdf slit --width 0
expect_error "unknown wdf kind"       wdf blob
expect_error "profile without file"   wdf profile
expect_error "missing profile file"   wdf profile --profile "$tmp/none.csv"
printf 'x,a,phi\n0,1,0\n0,1,0\n' >"$tmp/dup.csv"
expect_error "x not increasing"       wdf profile --profile "$tmp/dup.csv"
printf 'x,a,phi\n0,1,0\n1e-3,nan,0\n' >"$tmp/nan.csv"
expect_error "NaN in a profile"       wdf profile --profile "$tmp/nan.csv"
expect_error "wdf CSV to nowhere"     wdf slit --csv "$tmp/no/such/dir/w.csv"
expect_error "negative wdf extent"    wdf half-plane --extent -1e-6
expect_error "negative wdf u-range"   wdf slit --u-range -5
# An absurd --u-range is clamped to 2/λ: the table builds at once instead of running for ever.
if timeout 60 "$bin" wdf slit --u-range 1e10 --json >"$tmp/stdout" 2>"$tmp/stderr" &&
   grep -q '"u0_per_m":-4000000' "$tmp/stdout"; then
  passes=$((passes + 1))
else
  echo "FAIL: wdf slit --u-range 1e10 did not return promptly with the clamped range"; cat "$tmp/stderr"
  fails=$((fails + 1))
fi
expect_error "missing IR file"        metrics "$tmp/none.wav"
printf 'not audio\n' >"$tmp/text.wav"
expect_error "text file named .wav"   metrics "$tmp/text.wav"
# A 32-bit float WAV (format 3) holding 1.0 and NaN, byte by byte.
printf 'RIFF\x2c\x00\x00\x00WAVEfmt \x10\x00\x00\x00\x03\x00\x01\x00\x80\xbb\x00\x00\x00\xee\x02\x00\x04\x00\x20\x00data\x08\x00\x00\x00\x00\x00\x80\x3f\x00\x00\xc0\x7f' >"$tmp/nan.wav"
expect_error "NaN in a WAV"           metrics "$tmp/nan.wav"
printf 'RIFF\x2c\x00\x00\x00WAVEfmt \x10\x00\x00\x00\x03\x00\x01\x00\x80\xbb\x00\x00\x00\xee\x02\x00\x04\x00\x20\x00data\x08\x00\x00\x00\x00\x00\x80\x3f\x00\x00\x00\x3f' >"$tmp/ok.wav"
printf 'RIFF\x2c\x00\x00\x00WAVEfmt \x10\x00\x00\x00\x03\x00\x01\x00\x80\xbb\x00\x00\x00\xee\x02\x00\x04\x00\x20\x00data\x08\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00\x00' >"$tmp/silent.wav"
expect_error "a silent WAV"           metrics "$tmp/silent.wav"
printf 'RIFF\x2c\x00\x00\x00WAVEfmt \x10\x00\x00\x00\x03\x00\x01\x00\x96\x00\x00\x00\x58\x02\x00\x00\x04\x00\x20\x00data\x08\x00\x00\x00\x00\x00\x80\x3f\x00\x00\x00\x3f' >"$tmp/fs150.wav"
expect_error "150 Hz: no octave fits" metrics "$tmp/fs150.wav"
# At 12 kHz the 4 kHz octave's filter (up to ~5.7 kHz) fits below the 6 kHz Nyquist frequency: it is kept.
printf 'RIFF\x2c\x00\x00\x00WAVEfmt \x10\x00\x00\x00\x03\x00\x01\x00\xe0\x2e\x00\x00\x80\xbb\x00\x00\x04\x00\x20\x00data\x08\x00\x00\x00\x00\x00\x80\x3f\x00\x00\x00\x3f' >"$tmp/ok12k.wav"
if "$bin" metrics --json "$tmp/ok12k.wav" >"$tmp/stdout" 2>"$tmp/stderr" && grep -q '"4000"' "$tmp/stdout" &&
   ! grep -q '"8000"' "$tmp/stdout"; then passes=$((passes + 1)); else
  echo "FAIL: metrics: a 12 kHz file lost its 4 kHz octave (or kept 8 kHz)"; sed 's/^/    /' "$tmp/stdout" "$tmp/stderr"; fails=$((fails + 1)); fi
expect_error "channel 0"              metrics "$tmp/ok.wav" --channel 0
expect_error "channel past the last"  metrics "$tmp/ok.wav" --channel 2
expect_error "unknown band kind"      metrics "$tmp/ok.wav" --bands fifth
# diffray ir: a bad room file or option gives one line and leaves no WAV, JSON or CSV behind.
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
mat='"materials": {"w": {"absorption": 0.3, "scattering": 0.2}}'
box='"geometry": [{"box": {"min": [0,0,0], "max": [4,3,2.5], "materials": {"all": "w"}}}]'
src='"sources": [{"position": [1,1,1]}]'
lis='"listeners": [{"position": [3,2,1.2], "radius_m": 0.2}]'
good="{$mat, $box, $src, $lis}"
rm -f "$tmp/room.json"; "$bin" ir "$tmp/nope.json" -o "$tmp/out.wav" >/dev/null 2>"$tmp/stderr"
if [ $? -eq 2 ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] && ! ls "$tmp"/out.* >/dev/null 2>&1; then
  passes=$((passes + 1)); else echo "FAIL: ir: missing room file"; fails=$((fails + 1)); fi
expect_ir_error "malformed JSON"        "{$mat, $box, $src, $lis"
expect_ir_error "undefined material"    "{$mat, \"geometry\": [{\"box\": {\"min\": [0,0,0], \"max\": [4,3,2.5], \"materials\": {\"all\": \"nope\"}}}], $src, $lis}"
expect_ir_error "absorption above 1"    "{\"materials\": {\"w\": {\"absorption\": 1.5, \"scattering\": 0.2}}, $box, $src, $lis}"
expect_ir_error "infinite coordinate"   "{$mat, $box, \"sources\": [{\"position\": [1e999,1,1]}], $lis}"
expect_ir_error "null (NaN) coordinate" "{$mat, $box, \"sources\": [{\"position\": [null,1,1]}], $lis}"
expect_ir_error "source at 1e308 m (beyond float)" "{$mat, $box, \"sources\": [{\"position\": [1e308,1,1]}], $lis}"
expect_ir_error "missing OBJ"           "{$mat, \"geometry\": [{\"obj\": {\"file\": \"nope.obj\", \"default_material\": \"w\"}}], $src, $lis}"
expect_ir_error "zero listener radius"  "{$mat, $box, $src, \"listeners\": [{\"position\": [3,2,1.2], \"radius_m\": 0}]}"
expect_ir_error "no listeners"          "{$mat, $box, $src}"
expect_ir_error "unknown key"           "{$mat, $box, $src, $lis, \"ouptut\": {}}"
expect_ir_error "histograms past memory" "{$mat, $box, $src, $lis, \"output\": {\"max_length_s\": 600, \"ir_length_s\": 600, \"histogram_bin_s\": 1e-4}}"
expect_ir_error "nanosecond bins"       "{$mat, $box, $src, $lis, \"output\": {\"histogram_bin_s\": 1e-9}}"
expect_ir_error "zero rays"             "$good" --rays 0
expect_ir_error "lossless 1 cm box (endless bounces)" "{\"materials\": {\"w\": {\"absorption\": 0, \"scattering\": 0.2}}, \"geometry\": [{\"box\": {\"min\": [0,0,0], \"max\": [0.01,0.01,0.01], \"materials\": {\"all\": \"w\"}}}], \"sources\": [{\"position\": [0.005,0.005,0.005]}], \"listeners\": [{\"position\": [0.007,0.005,0.005], \"radius_m\": 0.001}]}" --rays 20000
expect_ir_error "8 kHz band at 8 kHz sampling" "{$mat, $box, $src, $lis, \"output\": {\"sample_rate_hz\": 8000}}"
expect_ir_error "one triangle, no volume" "{$mat, \"geometry\": [{\"polygon\": {\"vertices\": [[0,0,0],[1,0,0],[0,1,0]], \"material\": \"w\"}}], $src, $lis}"
expect_ir_error "ISM order out of range" "$good" --ism-order 99
# Refused when the file is loaded, naming the field (rooms/README.md, "The scene format").
expect_ir_says "8 kHz band at 16 kHz sampling" "output.sample_rate_hz: must exceed 22480 Hz" "{$mat, $box, $src, $lis, \"output\": {\"sample_rate_hz\": 16000}}"
expect_ir_says "fractional sample rate" "output.sample_rate_hz: must be a whole number" "{$mat, $box, $src, $lis, \"output\": {\"sample_rate_hz\": 44100.5}}"
expect_ir_says "default name taken" 'sources[1]: duplicate source name "S2"' "{$mat, $box, \"sources\": [{\"name\": \"S2\", \"position\": [1,1,1]}, {\"position\": [2,1,1]}], $lis}"
expect_ir_says "listener name with a comma" "must not contain a comma" "{$mat, $box, $src, \"listeners\": [{\"name\": \"R,1\", \"position\": [3,2,1.2]}]}"
expect_ir_says "material given twice" "materials.w: duplicate key" "{\"materials\": {\"w\": {\"absorption\": 0.3, \"scattering\": 0.2}, \"w\": {\"absorption\": 0.9, \"scattering\": 0.2}}, $box, $src, $lis}"
expect_ir_says "sources given twice" "sources: duplicate key" "{$mat, $box, $src, $src, $lis}"
expect_ir_says "OBJ file is a folder" "is a directory" "{$mat, \"geometry\": [{\"obj\": {\"file\": \".\", \"default_material\": \"w\"}}], $src, $lis}"
expect_ir_says "library is a folder" "materials_library: " "{\"materials_library\": \".\", $mat, $box, $src, $lis}"
printf 'v 0 0 0\nv 1 0 0\n' >"$tmp/nofaces.obj"
expect_ir_says "OBJ without faces" "has no faces" "{$mat, \"geometry\": [{\"obj\": {\"file\": \"nofaces.obj\", \"default_material\": \"w\"}}], $src, $lis}"
printf 'v 1 0 1\nv -0.809017 0.587785 1\nv 0.309017 -0.951057 1\nv 0.309017 0.951057 1\nv -0.809017 -0.587785 1\nf 1 2 3 4 5\n' >"$tmp/star.obj"
expect_ir_says "pentagram OBJ face" "star.obj:6: " "{$mat, \"geometry\": [{\"obj\": {\"file\": \"star.obj\", \"default_material\": \"w\"}}], $src, $lis}"
expect_ir_says "bow-tie polygon" "self-intersecting" "{$mat, \"geometry\": [{\"polygon\": {\"vertices\": [[1,1,1],[2,2,1],[2,1,1],[1,2,1]], \"material\": \"w\"}}], $src, $lis}"
# Occluders (rooms/README.md, "occluders") and the diffraction options.
door='"type": "door", "centre": [2,1.5,1], "normal": [1,0,0], "width_m": 0.9, "height_m": 2'
expect_ir_error "unknown occluder type" "{$mat, $box, $src, $lis, \"occluders\": [{\"type\": \"window\"}]}"
expect_ir_error "unknown occluder key"  "{$mat, $box, $src, $lis, \"occluders\": [{$door, \"sil\": \"none\"}]}"
expect_ir_error "occluder up along its normal" "{$mat, $box, $src, $lis, \"occluders\": [{$door, \"up\": [2,0,0]}]}"
expect_ir_error "door on a missing group" "{$mat, $box, $src, $lis, \"occluders\": [{\"type\": \"door\", \"group\": \"nope\"}]}"
expect_ir_error "zero-length edge"      "{$mat, $box, $src, $lis, \"occluders\": [{\"type\": \"edge\", \"start\": [1,1,1], \"end\": [1,1,1], \"open_toward\": [1,0,0]}]}"
expect_ir_error "duplicate occluder names" "{$mat, $box, $src, $lis, \"occluders\": [{$door, \"name\": \"d\"}, {$door, \"name\": \"d\"}]}"
expect_ir_error "unknown --diffraction" "$good" --diffraction bogus
expect_ir_error "--diffraction-order 0" "$good" --diffraction wbsdf --diffraction-order 0
printf '%s\n' "$good" >"$tmp/room.json"
expect_error "ir: output folder missing" ir "$tmp/room.json" -o "$tmp/no/such/dir/out.wav" --rays 1000
expect_error "ir: output not a .wav"     ir "$tmp/room.json" -o "$tmp/out.csv" --rays 1000

# A source outside the room is a warning, not an error: the run goes on and writes its outputs.
printf '%s\n' "{$mat, $box, \"sources\": [{\"position\": [9,1,1]}], $lis}" >"$tmp/room.json"
rm -f "$tmp"/out.*
if "$bin" ir "$tmp/room.json" -o "$tmp/out.wav" --rays 2000 >/dev/null 2>"$tmp/stderr" && grep -q "warning" "$tmp/stderr" &&
   [ -s "$tmp/out.wav" ] && [ -s "$tmp/out.json" ] && [ -s "$tmp/out.csv" ]; then passes=$((passes + 1)); else
  echo "FAIL: ir: a source outside the room should warn and go on"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi

# The room file's output.seed is the seed unless --seed is given (rooms/README.md): the sidecar says which
# was used, and --seed 77 on a file saying 1 gives the same WAV as a file saying 77.
mkdir -p "$tmp/in" "$tmp/o"
seeded() { printf '%s\n' "{$mat, $box, $src, $lis, \"output\": {\"seed\": $1, \"ir_length_s\": 0.2}}"; }
seeded 77 >"$tmp/in/s77.json"; seeded 1 >"$tmp/in/s1.json"
"$bin" ir "$tmp/in/s77.json" -o "$tmp/o/s77.wav" --rays 2000 >/dev/null 2>&1
"$bin" ir "$tmp/in/s1.json" -o "$tmp/o/s1.wav" --rays 2000 >/dev/null 2>&1
"$bin" ir "$tmp/in/s1.json" -o "$tmp/o/s1b.wav" --rays 2000 --seed 77 >/dev/null 2>&1
if grep -q '"seed": 77' "$tmp/o/s77.json" && grep -q '"seed": 1,' "$tmp/o/s1.json" &&
   cmp -s "$tmp/o/s77.wav" "$tmp/o/s1b.wav" && ! cmp -s "$tmp/o/s77.wav" "$tmp/o/s1.wav"; then
  passes=$((passes + 1)); else echo "FAIL: ir: the room file's output.seed is not the default seed"; fails=$((fails + 1)); fi

# Run in the room file's folder with the default output, the sidecar (ROOM.json) would be the room file:
# one line, non-zero exit, the room file untouched and no WAV or CSV written.
cp "$tmp/in/s1.json" "$tmp/in/keep.json"
(cd "$tmp/in" && "$bin" ir s1.json --rays 2000 >/dev/null 2>"$tmp/stderr")
code=$?
if [ "$code" -ne 0 ] && [ "$code" -lt 128 ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] && grep -q "would overwrite" "$tmp/stderr" && cmp -s "$tmp/in/s1.json" "$tmp/in/keep.json" &&
   ! ls "$tmp/in/s1.wav" "$tmp/in/s1.csv" >/dev/null 2>&1; then passes=$((passes + 1)); else
  echo "FAIL: ir: the default output overwrote the room file (exit=$code)"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi

# diffray compare: bad input gives one line and leaves no CSV or PNG behind.
rooms="$(cd "$(dirname "$0")/../rooms" && pwd)"

# No output may replace any file a run reads: the material library (ir's sidecar of -o materials.wav), the
# scene (compare --csv), a profile (wdf --csv). One line, non-zero exit, the input untouched.
mkdir -p "$tmp/lib"
cp "$rooms/shoebox.json" "$rooms/materials.json" "$rooms/barrier.json" "$tmp/lib/"
printf 'x,amplitude,phase\n-1e-4,1,0\n1e-4,1,0\n' >"$tmp/lib/p.csv"
cp -r "$tmp/lib" "$tmp/lib.keep"
expect_input_kept() {  # expect_input_kept DESCRIPTION KEPT_FILE ARGS...
  local what="$1" kept="$2"; shift 2
  (cd "$tmp/lib" && "$bin" "$@" >/dev/null 2>"$tmp/stderr")
  local code=$?
  if [ "$code" -ne 0 ] && [ "$code" -lt 128 ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] && grep -q "would overwrite" "$tmp/stderr" &&
     cmp -s "$tmp/lib/$kept" "$tmp/lib.keep/$kept"; then passes=$((passes + 1)); else
    echo "FAIL: $what (exit=$code)"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
}
expect_input_kept "ir: -o materials.wav would replace the library" materials.json ir shoebox.json -o materials.wav --rays 2000
expect_input_kept "compare: --csv onto the scene"                  barrier.json compare barrier.json --models utd --csv barrier.json
expect_input_kept "wdf: --csv onto the profile"                    p.csv wdf profile --profile p.csv --csv p.csv

# Names written into gnuplot scripts cannot run commands: a plot path with a newline is refused before any
# work (its message on one line), and a title with one is drawn as text (no file appears from the injected
# system()).
(cd "$tmp" && "$bin" validate slit-fraunhofer --rays 2000 --plot "p\"
system(\"touch pwned1\")
set output \"q.png" >/dev/null 2>"$tmp/stderr")
code=$?
if [ "$code" -ne 0 ] && [ "$code" -lt 128 ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] && grep -q "control character" "$tmp/stderr" &&
   [ ! -e "$tmp/pwned1" ] && ! ls "$tmp"/p* >/dev/null 2>&1; then passes=$((passes + 1)); else
  echo "FAIL: a plot path with a newline (exit=$code)"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
expect_compare_error() {  # expect_compare_error DESCRIPTION PATTERN ARGS...: the line must contain PATTERN
  local what="$1" pattern="$2"; shift 2
  expect_clean "compare: $what" "cmp.*" "$pattern" compare "$@"
}
fast=(--rays 1000 --fine-per-octave 2 --csv "$tmp/cmp.csv")
expect_compare_error "missing scene file"   "cannot open" "$tmp/none.json" "${fast[@]}"
printf '{"name": "broken", "sources": [\n' >"$tmp/broken.json"
expect_compare_error "malformed scene"      "JSON syntax error" "$tmp/broken.json" "${fast[@]}"
expect_compare_error "--models bogus"       'unknown model "bogus"' "$rooms/barrier.json" --models bogus "${fast[@]}"
expect_compare_error "--models empty"       "give at least one" "$rooms/barrier.json" --models "" "${fast[@]}"
expect_compare_error "--models ,"           'unknown model ""' "$rooms/barrier.json" --models , "${fast[@]}"
# Two barriers: --aim needs exactly one occluder to aim at.
python3 - "$rooms/barrier.json" "$tmp/two.json" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
second = dict(scene["occluders"][0], name="wall2", base=[[2, -20, 0], [2, 20, 0]])
scene["occluders"].append(second)
json.dump(scene, open(sys.argv[2], "w"))
PY
expect_compare_error "--aim with two occluders" "exactly one occluder" "$tmp/two.json" --aim "${fast[@]}"
expect_compare_error "CSV into a missing folder"  "folder does not exist" "$rooms/barrier.json" --rays 1000 --csv "$tmp/no/such/dir/cmp.csv"
expect_compare_error "plot into a missing folder" "folder does not exist" "$rooms/barrier.json" --rays 1000 --plot "$tmp/no/such/dir/cmp.png"
expect_compare_error "zero rays"            "--rays" "$rooms/barrier.json" --rays 0 "${fast[@]}"
expect_compare_error "--fine-per-octave 0"  "--fine-per-octave" "$rooms/barrier.json" --rays 1000 --fine-per-octave 0 --csv "$tmp/cmp.csv"
# Listeners compare cannot give a level for, each refused with one line naming it; --plot takes only .png.
python3 - "$rooms/barrier.json" "$tmp" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
for name, pos in [("high", [6, 0, 20]), ("atsrc", [-4, 0, 1]), ("onwall", [0, 0, 1]), ("under", [6, 0, -1])]:
    scene["listeners"] = [{"name": name, "position": pos, "radius_m": 0.15}]
    json.dump(scene, open(f"{sys.argv[2]}/l_{name}.json", "w"))
PY
expect_compare_error "--aim, listener seen past the zone" "listener high at (6, 0, 20) sees source S directly" "$tmp/l_high.json" --aim "${fast[@]}"
expect_compare_error "listener at the source" "listener atsrc at (-4, 0, 1) coincides with source S" "$tmp/l_atsrc.json" "${fast[@]}"
expect_compare_error "listener on the screen" "listener onwall at (0, 0, 1): its sphere" "$tmp/l_onwall.json" "${fast[@]}"
expect_compare_error "--plot x.svg"         "ending in .png" "$rooms/barrier.json" --rays 1000 --plot "$tmp/cmp.svg"
expect_clean "ir: --plot x.svg"             "out.*" "ending in .png" ir "$rooms/shoebox.json" -o "$tmp/out.wav" --rays 2000 --plot "$tmp/out.svg"
expect_clean "validate: --plot x.svg"       "out.*" "ending in .png" validate slit-fraunhofer --rays 1000 --plot "$tmp/out.svg"
# Two outputs in one file: refused before any work (one would silently replace the other).
expect_clean "validate: --csv = --plot"     "out.*" "two of this command's outputs" validate slit-fraunhofer --rays 1000 --csv "$tmp/out.png" --plot "$tmp/./out.png"
expect_compare_error "--csv = --plot"       "two of this command's outputs" "$rooms/barrier.json" --rays 1000 --csv "$tmp/cmp.png" --plot "$tmp/cmp.png"
# A listener below the ground: a warning naming it, and its missing WBSDF levels are empty CSV cells.
"$bin" compare "$tmp/l_under.json" --rays 2000 --fine-per-octave 2 --csv "$tmp/under.csv" >"$tmp/stdout" 2>"$tmp/stderr"
if [ $? -eq 0 ] && grep -q "listener under at (6, 0, -1) is outside the room" "$tmp/stderr" &&
   grep -q '^under,wbsdf,63,63,,,' "$tmp/under.csv" && ! grep -qi 'inf\|nan' "$tmp/under.csv"; then
  passes=$((passes + 1)); else echo "FAIL: compare: listener below the ground"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
# The table shows only what was computed; on a door the WBSDF is compared with the incoherent reference.
"$bin" compare "$rooms/barrier.json" --models wbsdf --rays 2000 >"$tmp/stdout" 2>"$tmp/stderr"
if [ $? -eq 0 ] && ! grep -q "exact reference\|nan\|utd" "$tmp/stdout" && grep -q "WBSDF 2000 rays" "$tmp/stdout"; then
  passes=$((passes + 1)); else echo "FAIL: compare: --models wbsdf table"; sed 's/^/    /' "$tmp/stdout"; fails=$((fails + 1)); fi
"$bin" compare "$rooms/barrier.json" --models utd,exact --fine-per-octave 2 >"$tmp/stdout" 2>"$tmp/stderr"
if [ $? -eq 0 ] && ! grep -q "WBSDF\|wbsdf\|nan" "$tmp/stdout" && grep -q "utd-exact" "$tmp/stdout"; then
  passes=$((passes + 1)); else echo "FAIL: compare: --models utd,exact table"; sed 's/^/    /' "$tmp/stdout"; fails=$((fails + 1)); fi
"$bin" compare "$rooms/doorway.json" --models wbsdf,exact --rays 2000 --fine-per-octave 2 >"$tmp/stdout" 2>"$tmp/stderr"
if [ $? -eq 0 ] && grep -q "wbsdf-exact-inc" "$tmp/stdout" && ! grep -q "wbsdf-exact " "$tmp/stdout"; then
  passes=$((passes + 1)); else echo "FAIL: compare: door table heading"; sed 's/^/    /' "$tmp/stdout"; fails=$((fails + 1)); fi
# --plot draws every listener: ten listeners and eight bands make 18 panels, 6 rows of 360 px (the old
# cap of six listeners gave 5 rows).
if command -v gnuplot >/dev/null 2>&1; then
  python3 - "$rooms/barrier.json" "$tmp/ten.json" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["listeners"] = [{"name": f"L{i}", "position": [6, 0, 0.5 + 0.6 * i], "radius_m": 0.15} for i in range(10)]
json.dump(scene, open(sys.argv[2], "w"))
PY
  "$bin" compare "$tmp/ten.json" --rays 2000 --fine-per-octave 2 --plot "$tmp/ten.png" >/dev/null 2>"$tmp/stderr"
  if [ "$(python3 -c "import struct,sys; print(struct.unpack('>I', open(sys.argv[1],'rb').read()[20:24])[0])" "$tmp/ten.png" 2>/dev/null)" = "2160" ]; then
    passes=$((passes + 1)); else echo "FAIL: compare: --plot did not draw all ten listeners"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
fi
# The good path: JSON lines with the documented keys, every model present, and a CSV with a header and the
# same rows.
"$bin" compare "$rooms/barrier.json" --aim --rays 20000 --fine-per-octave 2 --json --csv "$tmp/cmp.csv" \
  >"$tmp/cmp.jsonl" 2>"$tmp/stderr"
code=$?
if [ "$code" -eq 0 ] && python3 - "$tmp/cmp.jsonl" "$tmp/cmp.csv" <<'PY'
import csv, json, sys
rows = [json.loads(line) for line in open(sys.argv[1]) if line.strip()]
need = {"listener", "model", "freq_hz", "level_db_re_free_field"}
assert rows and all(need <= set(r) for r in rows), "a JSON line misses a key"
assert {r["model"] for r in rows} == {"wbsdf", "utd", "exact"}, {r["model"] for r in rows}
assert len({r["listener"] for r in rows}) == 7, "barrier.json has 7 listeners"
assert all(isinstance(r["freq_hz"], (int, float)) and r["freq_hz"] > 0 for r in rows)
table = list(csv.reader(open(sys.argv[2])))
assert table[0][:5] == ["listener", "model", "freq_hz", "band", "level_db_re_free_field"], table[0]
assert len(table) == len(rows) + 1, (len(table), len(rows))
PY
then passes=$((passes + 1)); else
  echo "FAIL: compare: good run (exit=$code) did not print the JSON lines and CSV"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi

# diffray auralize: bad input gives one line and leaves no WAV (nor a temporary) behind.
expect_auralize_error() {  # expect_auralize_error DESCRIPTION ARGS...
  local what="$1"; shift
  expect_clean "auralize: $what" "wet.*" "" auralize "$@"
}
# ok.wav at 44.1 kHz: the same two samples, another rate.
printf 'RIFF\x2c\x00\x00\x00WAVEfmt \x10\x00\x00\x00\x03\x00\x01\x00\x44\xac\x00\x00\x10\xb1\x02\x00\x04\x00\x20\x00data\x08\x00\x00\x00\x00\x00\x80\x3f\x00\x00\x00\x3f' >"$tmp/ok44.wav"
expect_auralize_error "missing IR file"        --ir "$tmp/none.wav" --in "$tmp/ok.wav" -o "$tmp/wet.wav"
expect_auralize_error "missing input file"     --ir "$tmp/ok.wav" --in "$tmp/none.wav" -o "$tmp/wet.wav"
expect_auralize_error "rate mismatch, --no-resample" --ir "$tmp/ok.wav" --in "$tmp/ok44.wav" -o "$tmp/wet.wav" --no-resample
# Without --no-resample the IR is resampled to the input's rate: one info line, a 44.1 kHz output.
if "$bin" auralize --ir "$tmp/ok.wav" --in "$tmp/ok44.wav" -o "$tmp/wet.wav" >"$tmp/stdout" 2>"$tmp/stderr" &&
   grep -q "resampled the impulse response from 48000 Hz to the input's 44100 Hz" "$tmp/stdout" &&
   grep -q "at 44100 Hz" "$tmp/stdout" && [ ! -s "$tmp/stderr" ]; then passes=$((passes + 1)); else
  echo "FAIL: auralize: a 48 kHz IR on a 44.1 kHz input was not resampled"; sed 's/^/    /' "$tmp/stdout" "$tmp/stderr"; fails=$((fails + 1)); fi
rm -f "$tmp"/wet.*
expect_auralize_error "NaN in the input"       --ir "$tmp/ok.wav" --in "$tmp/nan.wav" -o "$tmp/wet.wav"
expect_auralize_error "NaN in the input, normalized" --ir "$tmp/ok.wav" --in "$tmp/nan.wav" -o "$tmp/wet.wav" --normalize
expect_auralize_error "NaN in the IR"          --ir "$tmp/nan.wav" --in "$tmp/ok.wav" -o "$tmp/wet.wav"
expect_auralize_error "output folder missing"  --ir "$tmp/ok.wav" --in "$tmp/ok.wav" -o "$tmp/no/such/dir/wet.wav"
expect_auralize_error "output not a .wav"      --ir "$tmp/ok.wav" --in "$tmp/ok.wav" -o "$tmp/wet.csv"
expect_auralize_error "NaN gain"               --ir "$tmp/ok.wav" --in "$tmp/ok.wav" -o "$tmp/wet.wav" --gain nan
expect_auralize_error "no --in"                --ir "$tmp/ok.wav" -o "$tmp/wet.wav"
# --gain is bounded like door's (±120 dB) when parsing, not after the whole convolution.
expect_clean "auralize: gain 200 dB"       "wet.*" "--gain" auralize --ir "$tmp/ok.wav" --in "$tmp/ok.wav" -o "$tmp/wet.wav" --gain 200
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
expect_clean "door --steps 2.5"        "door.*" "--steps: must be a whole number" door "$two" --in "$tmp/burst.wav" -o "$tmp/door.wav" --close 0.1:0.2 --steps 2.5
expect_clean "wdf --count 2.5"         "out.csv*" "--count: must be a whole number" wdf slits --count 2.5 "$csv"
expect_clean "wdf --count 0x3"         "out.csv*" "--count: must be a whole number" wdf slits --count 0x3 "$csv"
expect_clean "--threads 1.5"           "out.csv*" "--threads: must be a whole number" validate slit-fraunhofer --rays 1000 --threads 1.5 "$csv"
expect_clean "signal --rate 48000.5"   "sig.*" "--rate: must be a whole number" signal clicks -o "$tmp/sig.wav" --rate 48000.5
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

echo "cli_bad_input: $passes passed, $fails failed"
[ "$fails" -eq 0 ]
