#!/bin/bash
# Runs the README's "Your first room" walkthrough verbatim, block by block in order, in a temporary folder
# laid out like the repository (build/diffray and rooms/ linked in), then its Python example when the module
# is built (PYTHONPATH given). Each block must exit 0; then the files the walkthrough names must exist and
# hold what they claim: a WAV with one channel per listener, a sidecar with finite T30 at every listener
# and band, and a comparison CSV with the three models at every listener of two-rooms.
# Usage: readme_walkthrough.sh DIFFRAY_BINARY REPOSITORY [PYTHONPATH PYTHON]
set -u
bin="$(cd "$(dirname "$1")" && pwd)/$(basename "$1")"
repo="$(cd "$2" && pwd)"
pypath="${3:-}"
python="${4:-python3}"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
mkdir -p "$tmp/build"
ln -s "$bin" "$tmp/build/diffray"
ln -s "$repo/rooms" "$tmp/rooms"

python3 - "$repo/README.md" "$tmp" <<'PY' || exit 1
import re, sys
readme, tmp = sys.argv[1], sys.argv[2]
text = open(readme).read()
def section(title):
    a = text.index("## " + title)
    b = text.find("\n## ", a + 3)
    return text[a:b if b > 0 else len(text)]
blocks = re.findall(r"```sh\n(.*?)```", section("Your first room"), re.S)
if len(blocks) < 4:
    sys.exit(f"FAIL: expected the walkthrough's command blocks, found {len(blocks)}")
for i, b in enumerate(blocks):
    open(f"{tmp}/block{i:02d}.sh", "w").write("set -euo pipefail\n" + b)
py = re.findall(r"```python\n(.*?)```", section("From Python"), re.S)
if py:
    open(f"{tmp}/example.py", "w").write(py[0])
PY

fails=0
cd "$tmp" || exit 1
for b in block*.sh; do
  if ! bash "$b" >"$b.out" 2>"$b.err"; then
    echo "FAIL: walkthrough $b exited non-zero:"; sed 's/^/    /' "$b"; tail -5 "$b.err" | sed 's/^/    /'
    fails=$((fails + 1))
  fi
done
[ "$fails" -eq 0 ] && python3 - <<'PY' || fails=$((fails + 1))
import csv, json, math, subprocess, sys
bad = []
side = json.load(open("my-room/office-ir.json"))
names = [l["name"] for l in side["listeners"]]
if names != ["desk", "door"]:
    bad.append(f"sidecar listeners {names}")
for l in side["listeners"]:
    for band, m in l["bands"].items():
        t30 = m.get("t30")
        if t30 is None or not math.isfinite(t30) or t30 <= 0:
            bad.append(f"{l['name']} {band} Hz: T30 {t30}")
info = subprocess.run(["soxi", "-c", "my-room/office-ir.wav"], capture_output=True, text=True)
if info.returncode == 0 and info.stdout.strip() != "2":
    bad.append(f"office-ir.wav has {info.stdout.strip()} channels, not 2")
for f in ["my-room/decay.png", "my-room/dry.wav", "my-room/wet.wav", "my-room/wet.png", "my-room/two-rooms.wav",
          "my-room/two-rooms-3d.B-hidden.binaural.wav", "my-room/door.wav", "my-room/directions.png"]:
    import os
    if not os.path.exists(f) or os.path.getsize(f) == 0:
        bad.append(f"{f} missing or empty")
rows = list(csv.DictReader(open("my-room/two-rooms-compare.csv")))
seen = {(r["listener"], r["model"]) for r in rows}
for lis in ["A", "B-in-view", "B-hidden"]:
    for model in ["none", "utd", "wbsdf"]:
        if (lis, model) not in seen:
            bad.append(f"compare CSV lacks {lis}/{model}")
for b in bad:
    print("FAIL:", b)
sys.exit(1 if bad else 0)
PY
if [ -n "$pypath" ] && [ -f example.py ]; then
  if ! PYTHONPATH="$pypath" "$python" example.py >example.out 2>example.err; then
    echo "FAIL: the README's Python example:"; tail -5 example.err | sed 's/^/    /'; fails=$((fails + 1))
  elif [ -f my-room/office-ir.json ]; then
    # The example is the walkthrough's office (one listener, same seed): its T30 must be the CLI's at "desk".
    python3 - <<'PY' || fails=$((fails + 1))
import json, re, sys
out = open("example.out").read()
m = re.search(r"T30 at 1 kHz = ([0-9.]+) s", out)
cli = json.load(open("my-room/office-ir.json"))["listeners"][0]["bands"]["1000"]["t30"]
if not m or m.group(1) != f"{cli:.2f}":
    sys.exit(f"FAIL: the Python example printed {out.strip()!r}; the CLI's T30 at desk, 1 kHz, is {cli:.2f} s")
PY
  fi
fi
if [ "$fails" -ne 0 ]; then echo "readme_walkthrough: $fails failure(s)"; exit 1; fi
echo "readme_walkthrough: every block ran, outputs checked"
