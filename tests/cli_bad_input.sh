#!/usr/bin/env bash
# Bad input to the diffray CLI must give exactly one line on stderr, a non-zero exit code and no output
# file (design: never a crash, never a half-written output). This script covers validate, wdf, metrics, ir
# and compare; cli_bad_input_media.sh the other commands, cli_lib.sh holds what both share.
# Usage: cli_bad_input.sh PATH/TO/diffray
set -u
. "$(dirname "$0")/cli_lib.sh"

expect_error "zero-width slit"        validate slit-fraunhofer --width 0 --rays 1000 "$csv"
expect_error "negative width"         validate double-slit --width -1e-4 --rays 1000 "$csv"
expect_error "zero wavelength"        validate slit-fresnel --wavelength 0 --rays 1000 "$csv"
expect_error "NaN width"              validate slit-fraunhofer --width nan --rays 1000 "$csv"
expect_error "distance 1e30 m (beyond float)" validate slit-fraunhofer --distance 1e30 --rays 1000 "$csv"
expect_error "half-plane source at 1e30 m"    validate half-plane --source-distance 1e30 --rays 1000 "$csv"
expect_error "door-rs at 900 kHz"     validate door-rs --freq 9e5 --rays 1000 "$csv"
expect_error "infinite distance"      validate slit-fraunhofer --distance inf --rays 1000 "$csv"
expect_error "negative frequency"     validate door-rs --freq 125,-250 --rays 1000 "$csv"
expect_error "door past the shared wall"  validate two-rooms-wave --door-position 3.5 --rays 1000 "$csv"
expect_error "listener outside the rooms" validate classroom-wave --listeners 20,1,1 --rays 1000 "$csv"
expect_error "spacing below width"    validate double-slit --width 1e-4 --spacing 5e-5 --rays 1000 "$csv"
expect_error "unknown case"           validate no-such-case "$csv"
expect_error "image: spacing below width" validate image-double-slit --width 1e-4 --spacing 5e-5 --rays 1000 "$csv"
expect_error "image: infrared"       validate image-double-slit --wavelength 1e-6 --rays 1000 "$csv"
expect_error "unknown option"         validate slit-fraunhofer --no-such-option 3 "$csv"
expect_error "option of another case" validate slit-fraunhofer --spacing 1e-4 --rays 1000 "$csv"
# A parameter takes one value unless it is a list (door-rs --freq): the case would read the first and drop
# the rest. Counts are whole numbers; numbers are decimal (strtod reads 0x10 as 16).
expect_clean "two widths"             "out.csv*" "--width: takes one value, got 2" validate slit-fraunhofer --width 1e-4,2e-4 --rays 1000 "$csv"
expect_clean "hexadecimal width"      "out.csv*" "--width: must be a number" validate slit-fraunhofer --width 0x10 --rays 1000 "$csv"
expect_clean "fractional bins"        "out.csv*" "--bins: must be a whole number" validate slit-fraunhofer --bins 150.5 --rays 1000 "$csv"
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
# metrics reads cli_lib.sh's text.wav, nan.wav and ok.wav; the other WAVs are written here.
expect_error "missing IR file"        metrics "$tmp/none.wav"
expect_error "text file named .wav"   metrics "$tmp/text.wav"
expect_error "NaN in a WAV"           metrics "$tmp/nan.wav"
# A 169-byte FLAC whose header claims 2^36 - 1 frames: refused before work, the message saying it is a claim.
flac_claiming "$tmp/lie.flac" 68719476735
expect_clean "metrics: a header claiming 2^36 - 1 frames" "out.csv*" "its header claims 68719476735 frames" \
  metrics "$tmp/lie.flac"
# ok.wav's header with two zero samples.
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
# diffray ir: a bad room file or option gives one line and leaves no WAV, JSON or CSV behind (expect_ir_says,
# expect_ir_error and the room parts mat, box, src and lis are in cli_lib.sh).
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
expect_ir_error "--format unknown"      "$good" --format binaural5
expect_ir_error "--order 4 (Ambisonics to 3)" "$good" --format ambix --order 4
printf 'not a SOFA file\n' >"$tmp/bad.sofa"
expect_ir_error "--hrtf: not a SOFA file" "$good" --format binaural --hrtf "$tmp/bad.sofa"
expect_ir_error "--hrtf: missing file"  "$good" --format binaural --hrtf "$tmp/none.sofa"
expect_ir_error "--hrtf without binaural" "$good" --hrtf "$tmp/bad.sofa"
# A 48 kHz SOFA set (two directions, made by ncgen from CDL; Debian's netcdf-bin; the global attributes SOFA
# requires, without which libmysofa 1.3.1 cannot read the file): read as is for a 48 kHz room, resampled for
# a 44.1 kHz one, and `ir` says so in its one HRTF info line.
if command -v ncgen >/dev/null; then
  cat >"$tmp/set48.cdl" <<'CDL'
netcdf set48 {
dimensions: M = 2 ; R = 2 ; N = 4 ; E = 1 ; C = 3 ; I = 1 ;
variables:
  double ListenerPosition(I, C) ; ListenerPosition:Type = "cartesian" ;
  double ReceiverPosition(R, C, I) ; ReceiverPosition:Type = "cartesian" ;
  double SourcePosition(M, C) ; SourcePosition:Type = "spherical" ;
  double EmitterPosition(E, C, I) ; EmitterPosition:Type = "cartesian" ;
  double Data.IR(M, R, N) ;
  double Data.SamplingRate(I) ; Data.SamplingRate:Units = "hertz" ;
  :Conventions = "SOFA" ; :SOFAConventions = "SimpleFreeFieldHRIR" ; :DataType = "FIR" ; :RoomType = "free field" ;
  :Version = "1.0" ; :SOFAConventionsVersion = "1.0" ; :APIName = "tests" ; :APIVersion = "1.0" ; :Title = "set48" ;
  :AuthorContact = "-" ; :Organization = "-" ; :License = "-" ; :DateCreated = "-" ; :DateModified = "-" ;
data:
  ListenerPosition = 0, 0, 0 ; ReceiverPosition = 0, 0.09, 0, 0, -0.09, 0 ; EmitterPosition = 0, 0, 0 ;
  SourcePosition = 90, 0, 1, 270, 0, 1 ;
  Data.IR = 1, 0, 0, 0,  0, 0, 1, 0,  0, 0, 1, 0,  1, 0, 0, 0 ;
  Data.SamplingRate = 48000 ;
}
CDL
  ncgen -k nc4 "$tmp/set48.cdl" -o "$tmp/set48.sofa"
  for rate in 48000 44100; do
    printf '%s\n' "{$mat, $box, $src, $lis, \"output\": {\"sample_rate_hz\": $rate}}" >"$tmp/room.json"
    "$bin" ir "$tmp/room.json" -o "$tmp/out.wav" --rays 2000 --format binaural --hrtf "$tmp/set48.sofa" \
      >/dev/null 2>"$tmp/stderr"
    code=$?
    info=$(grep -c '^diffray: info: HRTF ' "$tmp/stderr")
    if [ "$rate" = 48000 ]; then said="set48.sofa (2 directions)$"; else said="set48.sofa (2 directions, resampled from 48000 to 44100 Hz)$"; fi
    if [ "$code" -eq 0 ] && [ "$info" -eq 1 ] && grep -q "^diffray: info: HRTF .*$said" "$tmp/stderr"; then
      passes=$((passes + 1)); else echo "FAIL: ir --hrtf, a 48 kHz set at $rate Hz: exit=$code"; sed 's/^/    /' "$tmp/stderr"
      fails=$((fails + 1)); fi
    rm -f "$tmp"/out.*
  done
else
  echo "note: ncgen is not installed (Debian's netcdf-bin, tools/deps.sh): the 48 kHz SOFA set's checks skipped"
fi
expect_ir_says "--plot-directions x.svg" "ending in .png" "$good" --plot-directions "$tmp/out.svg"
expect_ir_error "listener look_at itself" "{$mat, $box, $src, \"listeners\": [{\"position\": [1,1,1], \"look_at\": [1,1,1]}]}"
printf '%s\n' "$good" >"$tmp/room.json"
expect_error "ir: output folder missing" ir "$tmp/room.json" -o "$tmp/no/such/dir/out.wav" --rays 1000
expect_error "ir: output not a .wav"     ir "$tmp/room.json" -o "$tmp/out.csv" --rays 1000

# A source outside the room is a warning, not an error: the run goes on and writes its outputs.
printf '%s\n' "{$mat, $box, \"sources\": [{\"position\": [9,1,1]}], $lis}" >"$tmp/room.json"
rm -f "$tmp"/out.*
if "$bin" ir "$tmp/room.json" -o "$tmp/out.wav" --rays 2000 >/dev/null 2>"$tmp/stderr" && grep -q "warning" "$tmp/stderr" &&
   [ -s "$tmp/out.wav" ] && [ -s "$tmp/out.json" ] && [ -s "$tmp/out.csv" ]; then passes=$((passes + 1)); else
  echo "FAIL: ir: a source outside the room should warn and go on"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
# So with a closed object in the open (rooms/cupboard.json: a rigid box on a ground, the source outside it):
# the box's volume does not bound the rays' paths (they leave into free space), so no "too many wall hits";
# a warning names compare as the command for such scenes.
rm -f "$tmp"/out.*
if "$bin" ir "$rooms/cupboard.json" -o "$tmp/out.wav" --rays 2000 >/dev/null 2>"$tmp/stderr" &&
   grep -q "source S at (0, -2, 1) is outside the room" "$tmp/stderr" && ! grep -q "wall hits" "$tmp/stderr" &&
   grep -q "no source is inside an enclosed room: .*use diffray compare$" "$tmp/stderr" &&
   [ -s "$tmp/out.wav" ] && [ -s "$tmp/out.json" ]; then passes=$((passes + 1)); else
  echo "FAIL: ir: a source outside a closed object should warn and go on"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi

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

# ir prints the room's Sabine and Eyring T beside the traced T30, in the table and the sidecar, and notes the
# bands where traced T30 and Eyring differ by more than 1.5x (the shoebox: hard walls, absorbing floor and
# ceiling, a field far from diffuse: traced T30 about 6x Eyring's at 1 kHz).
"$bin" ir "$rooms/shoebox.json" --rays 20000 -o "$tmp/stat.wav" >"$tmp/stat.txt" 2>"$tmp/stderr"
if grep -q "Sabine T s  Eyring T s  traced T30 s" "$tmp/stat.txt" && grep -q "note: the traced T30 differs from Eyring's by more than a factor 1.5 (.*1000 Hz" "$tmp/stderr" &&
   python3 -c "
import json, sys
s = json.load(open('$tmp/stat.json'))['statistical_reverberation']
b = s['bands']['1000']
sys.exit(0 if abs(s['volume_m3'] - 210) < 1e-6 and b['eyring_s'] < b['sabine_s'] < b['traced_t30_s'] and 'note' in s else 1)"; then
  passes=$((passes + 1)); else echo "FAIL: ir: Sabine/Eyring beside the traced T30"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
rm -f "$tmp"/stat.*
# metrics --spatial: the shoebox's two listeners as a two-channel file give IACC per band (and averages, in
# the table and the JSON); a file of the wrong channel count is one line and nothing else.
"$bin" ir "$rooms/shoebox.json" --rays 20000 -o "$tmp/two.wav" >/dev/null 2>&1
if "$bin" metrics "$tmp/two.wav" --spatial binaural >"$tmp/sp.txt" 2>"$tmp/stderr" &&
   grep -q "IACC_E3 (500 Hz - 2 kHz)" "$tmp/sp.txt" && grep -q "^ *1000 *0\.[0-9]* *0\.[0-9]*$" "$tmp/sp.txt" &&
   "$bin" metrics "$tmp/two.wav" --spatial binaural --json | python3 -c "
import json, sys
s = json.load(sys.stdin)['spatial']
sys.exit(0 if s['format'] == 'binaural' and 0 <= s['bands']['1000']['iacc_e'] <= 1.01 and 'iacc_e3' in s else 1)"; then
  passes=$((passes + 1)); else echo "FAIL: metrics --spatial binaural"; sed 's/^/    /' "$tmp/sp.txt" "$tmp/stderr"; fails=$((fails + 1)); fi
expect_error "metrics --spatial ambix on two channels" metrics "$tmp/two.wav" --spatial ambix
expect_error "metrics --spatial binaural on one channel" metrics "$tmp/ok.wav" --spatial binaural
expect_error "metrics --spatial of an unknown kind" metrics "$tmp/two.wav" --spatial stereo
rm -f "$tmp"/two.* "$tmp"/sp.txt

# Run in the room file's folder with the default output: ROOM.ir.wav, .ir.json, .ir.csv, the room file untouched.
cp "$tmp/in/s1.json" "$tmp/in/keep.json"
(cd "$tmp/in" && "$bin" ir s1.json --rays 2000 >/dev/null 2>"$tmp/stderr")
code=$?
if [ "$code" -eq 0 ] && cmp -s "$tmp/in/s1.json" "$tmp/in/keep.json" &&
   [ -s "$tmp/in/s1.ir.wav" ] && [ -s "$tmp/in/s1.ir.json" ] && [ -s "$tmp/in/s1.ir.csv" ]; then passes=$((passes + 1)); else
  echo "FAIL: ir: the default output beside the room file (exit=$code)"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi

# diffray compare: bad input gives one line and leaves no CSV or PNG behind.

# No output may replace any file a run reads: the material library (ir's sidecar of -o materials.wav), the
# scene (compare --csv), a profile (wdf --csv). One line, non-zero exit, the input untouched.
# (The inputs are in cli_lib.sh's $tmp/lib; lib.keep is the copy they are compared with.)
cp -r "$tmp/lib" "$tmp/lib.keep"
expect_input_kept() {  # expect_input_kept DESCRIPTION KEPT_FILE ARGS...
  local what="$1" kept="$2"; shift 2
  (cd "$tmp/lib" && "$bin" "$@" >/dev/null 2>"$tmp/stderr")
  local code=$?
  if [ "$code" -ne 0 ] && [ "$code" -lt 128 ] && [ "$(wc -l <"$tmp/stderr")" -eq 1 ] && grep -q "would overwrite" "$tmp/stderr" &&
     cmp -s "$tmp/lib/$kept" "$tmp/lib.keep/$kept"; then passes=$((passes + 1)); else
    echo "FAIL: $what (exit=$code)"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
}
# ir's outputs beside the scene: the default names carry ".ir" (shoebox.ir.wav, .ir.json, .ir.csv), and with
# -o X.wav a sidecar that would be an input (X.json the scene or the library) becomes X.ir.json, with a note.
expect_ir_beside() {  # expect_ir_beside DESCRIPTION "FILES WRITTEN" ARGS...
  local what="$1" files="$2"; shift 2
  (cd "$tmp/lib" && "$bin" "$@" >/dev/null 2>"$tmp/stderr")
  local code=$? f ok=1
  for f in $files; do [ -s "$tmp/lib/$f" ] || ok=0; done
  for f in shoebox.json materials.json; do cmp -s "$tmp/lib/$f" "$tmp/lib.keep/$f" || ok=0; done
  if [ "$code" -eq 0 ] && [ "$ok" -eq 1 ]; then passes=$((passes + 1)); else
    echo "FAIL: $what (exit=$code)"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
  (cd "$tmp/lib" && rm -f $files)
}
expect_ir_beside "ir: default names beside the scene" "shoebox.ir.wav shoebox.ir.json shoebox.ir.csv" ir shoebox.json --rays 2000
expect_ir_beside "ir: -o shoebox.wav beside shoebox.json" "shoebox.wav shoebox.ir.json shoebox.ir.csv" ir shoebox.json -o shoebox.wav --rays 2000
grep -q "note: shoebox.json is an input" "$tmp/stderr" && passes=$((passes + 1)) ||
  { echo "FAIL: ir -o shoebox.wav: no note on the sidecar's name"; fails=$((fails + 1)); }
expect_ir_beside "ir: -o materials.wav keeps the library" "materials.wav materials.ir.json materials.ir.csv" ir shoebox.json -o materials.wav --rays 2000
# render -o cd.png beside cd.json: the sidecar becomes cd.render.json, with a note; the scene is untouched.
cp "$rooms/light/cd.json" "$tmp/lib/cd.json"
(cd "$tmp/lib" && "$bin" render cd.json -o cd.png --photons 2000 >/dev/null 2>"$tmp/stderr")
if [ $? -eq 0 ] && cmp -s "$tmp/lib/cd.json" "$rooms/light/cd.json" && [ -s "$tmp/lib/cd.render.json" ] &&
   [ -s "$tmp/lib/cd.png" ] && grep -q "note: cd.json is the scene, so the sidecar is cd.render.json" "$tmp/stderr"; then
  passes=$((passes + 1)); else echo "FAIL: render -o cd.png beside cd.json"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
rm -f "$tmp/lib/cd."*
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
# A reflecting ground that scatters under the barrier: aimed rays would drop its diffuse reflections.
python3 - "$rooms/barrier.json" "$tmp/rigid_ground.json" <<'PY'
import json, sys
scene = json.load(open(sys.argv[1]))
scene["materials"]["absorbing-ground"]["absorption"] = 0.2
scene["materials"]["absorbing-ground"]["scattering"] = 0.3
json.dump(scene, open(sys.argv[2], "w"))
PY
expect_compare_error "--aim over a diffusing ground" "surface ground (absorbing-ground) scatters sound diffusely" "$tmp/rigid_ground.json" --aim "${fast[@]}"
expect_compare_error "CSV into a missing folder"  "folder does not exist" "$rooms/barrier.json" --rays 1000 --csv "$tmp/no/such/dir/cmp.csv"
expect_compare_error "plot into a missing folder" "folder does not exist" "$rooms/barrier.json" --rays 1000 --plot "$tmp/no/such/dir/cmp.png"
expect_compare_error "zero rays"            "--rays" "$rooms/barrier.json" --rays 0 "${fast[@]}"
expect_compare_error "--fine-per-octave 0"  "--fine-per-octave" "$rooms/barrier.json" --rays 1000 --fine-per-octave 0 --csv "$tmp/cmp.csv"
expect_compare_error "--freq 0"             "--freq: each frequency must lie in (0, 100000] Hz, got 0" "$rooms/barrier.json" --rays 1000 --freq 0 --csv "$tmp/cmp.csv"
expect_compare_error "--freq 2e5"           "--freq: each frequency must lie in (0, 100000] Hz" "$rooms/barrier.json" --rays 1000 --freq 250,2e5 --csv "$tmp/cmp.csv"
expect_compare_error "room mode: --freq"    "--freq: applies to free-field scenes only" "$rooms/two-rooms.json" --freq 250 "${fast[@]}"
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
# Room mode (a closed room holding its source: two-rooms.json): its options refused by name, the free-field
# mode's aperture reference refused naming the listener it cannot describe; a run gives every model for every
# listener and says once, for listener A only, why the free-field reference is not shown.
expect_compare_error "--mode bogus"          "--mode" "$rooms/two-rooms.json" --mode bogus "${fast[@]}"
expect_compare_error "room mode: --aim"      "--aim: applies to free-field scenes only" "$rooms/two-rooms.json" --aim "${fast[@]}"
expect_compare_error "room mode: --models"   'unknown model "bogus" in room mode' "$rooms/two-rooms.json" --models none,bogus "${fast[@]}"
expect_compare_error "free-field mode on a room" "listener A: model exact: on the source's side" "$rooms/two-rooms.json" --mode free-field "${fast[@]}"
# Room mode with the wave reference: its checks (bands, memory) before any model runs.
expect_compare_error "room mode: wave band not in the room" "not one of the room's band" "$rooms/two-rooms.json" --models none,wave --wave-bands 300 "${fast[@]}"
expect_compare_error "room mode: wave grid too large" "more than half of this machine" "$rooms/two-rooms.json" --models none,wave --wave-bands 8000 --wave-ppw 100 "${fast[@]}"
expect_compare_error "free-field mode: no wave model" 'unknown model "wave" in free-field mode' "$rooms/barrier.json" --models wave
"$bin" compare "$rooms/two-rooms.json" --rays 2000 --csv "$tmp/room.csv" >"$tmp/stdout" 2>"$tmp/stderr"
if [ $? -eq 0 ] && [ "$(grep -c '^A,\|^B-in-view,\|^B-hidden,' "$tmp/room.csv")" -eq $((3 * 3 * 8 + 2 * 8)) ] &&
   [ "$(grep -c 'not shown, on the source' "$tmp/stdout")" -eq 1 ] && grep -q "room mode" "$tmp/stdout" &&
   ! grep -qiw 'inf\|nan' "$tmp/stdout" "$tmp/room.csv" && ! grep -q 'z_m' "$tmp/stdout" && [ ! -s "$tmp/stderr" ]; then
  passes=$((passes + 1)); else echo "FAIL: compare: room mode on two-rooms"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi
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
assert table[0][-1] == "phase_deg_re_free_field", table[0]
assert len(table) == len(rows) + 1, (len(table), len(rows))
fine = [r for r in rows if not r["band"] and r["model"] != "wbsdf"]
assert fine and all(-180 <= r["phase_deg_re_free_field"] <= 180 for r in fine), "fine rows carry a phase"
PY
then passes=$((passes + 1)); else
  echo "FAIL: compare: good run (exit=$code) did not print the JSON lines and CSV"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1)); fi

# diffray wave (the FDTD reference): one line before any work, no JSON or CSV left.
expect_wave_says() {  # expect_wave_says DESCRIPTION PATTERN ROOM_JSON_TEXT [ARGS...]
  local what="$1" pattern="$2" text="$3"; shift 3
  printf '%s\n' "$text" >"$tmp/room.json"
  expect_clean "wave: $what" "out.*" "$pattern" wave "$tmp/room.json" -o "$tmp/out.json" --csv "$tmp/out.csv" "$@"
}
pillar='{"box": {"min": [1,1,0], "max": [2,2,2.5], "materials": {"all": "w"}}}'
expect_wave_says "grid too large"       "more than half of this machine" "{$mat, $box, $src, $lis}" --bands 8000 --ppw 100
expect_wave_says "band not in the room" "not one of the room's band"   "{$mat, $box, $src, $lis}" --bands 300
expect_wave_says "too few points per wavelength" "ppw" "{$mat, $box, $src, $lis}" --ppw 2
expect_wave_says "source outside the closed room" "outside the room" \
  "{$mat, $box, \"sources\": [{\"position\": [5,1,1]}], $lis}" --bands 63
expect_wave_says "source just outside the closed room" "outside the room" \
  "{$mat, $box, \"sources\": [{\"position\": [4.2,1,1]}], $lis}" --bands 63
expect_wave_says "source inside a pillar" "inside a wall" \
  "{$mat, \"geometry\": [{\"box\": {\"min\": [0,0,0], \"max\": [4,3,2.5], \"materials\": {\"all\": \"w\"}}}, $pillar], \"sources\": [{\"position\": [1.5,1.5,1]}], $lis}" --bands 63
expect_wave_says "listener outside the air" "no air node" \
  "{$mat, $box, $src, \"listeners\": [{\"position\": [5,1,1], \"radius_m\": 0.2}]}" --bands 63
expect_wave_says "listener inside a pillar" "no air node" \
  "{$mat, \"geometry\": [{\"box\": {\"min\": [0,0,0], \"max\": [4,3,2.5], \"materials\": {\"all\": \"w\"}}}, $pillar], $src, \"listeners\": [{\"position\": [1.5,1.5,1], \"radius_m\": 0.2}]}" --bands 63

finish cli_bad_input
