#!/bin/bash
# diffray ir's marks on noisy and negative-energy bands, end to end through the CLI: two-rooms with WBSDF
# diffraction (the plain signed estimator, --wbsdf-continuation wigner) at 3000 rays per source (a few seconds), where bands of the listeners behind the door sum
# negative. Each band that sums negative (from the CSV histograms, summed here) must be flagged
# "negative_energy" in the sidecar with null figures (histogram and WAV alike), be named in one warning on
# stderr and in the sidecar's warnings, and show no number in its table rows; every band flagged ok has no
# warning; every band has its standard errors and the keys the sidecar had before.
set -u
. "$(dirname "$0")/cli_lib.sh"
rooms="$(cd "$(dirname "$0")/../rooms" && pwd)"

"$bin" ir "$rooms/two-rooms.json" --diffraction wbsdf --wbsdf-continuation wigner --rays 3000 --length 0.5 --seed 1 -o "$tmp/out.wav" \
  >"$tmp/table.txt" 2>"$tmp/stderr"
code=$?
if [ "$code" -ne 0 ]; then
  echo "FAIL: ir exited $code"; sed 's/^/    /' "$tmp/stderr"; fails=$((fails + 1))
else
  python3 - "$tmp" <<'PY'
import csv, json, sys
tmp = sys.argv[1]
side = json.load(open(f"{tmp}/out.json"))
stderr = open(f"{tmp}/stderr").read()
table = open(f"{tmp}/table.txt").read()
sums = {}
for row in csv.DictReader(open(f"{tmp}/out.csv")):
    for key, v in row.items():
        if key.startswith("e_"):
            k = (row["listener"], key[2:-2])
            sums[k] = sums.get(k, 0.0) + float(v)
failures, negative = [], 0
old_keys = ["t20", "t30", "edt", "c50", "c80", "d50", "ts", "decay_range_db"]
for l in side["listeners"]:
    assert "negative_energy_fraction" in l
    for band, v in l["bands"].items():
        where = f"listener {l['name']}, {band} Hz"
        wav = l["bands_from_wav"][band]
        for d in (v, wav):
            for key in old_keys + ["se", "flag", "negative_energy_fraction"]:
                if key not in d:
                    failures.append(f"{where}: no key {key}")
        warned = [w for w in side["warnings"] if w.startswith(where + ":")]
        on_stderr = [w for w in stderr.splitlines() if w.startswith("diffray: warning: " + where + ":")]
        if sums[(l["name"], band)] < 0:
            negative += 1
            if v["flag"] != "negative_energy" or wav["flag"] != "negative_energy":
                failures.append(f"{where}: sums negative, flagged {v['flag']} / {wav['flag']}")
            if any(v[k] is not None for k in old_keys[:7]) or any(wav[k] is not None for k in old_keys[:7]):
                failures.append(f"{where}: sums negative but has figures")
            if len(warned) != 1 or "energy sums negative" not in warned[0] or len(on_stderr) != 1:
                failures.append(f"{where}: sums negative, warnings {warned} / {on_stderr}")
        elif v["flag"] == "ok" and warned:
            failures.append(f"{where}: ok but warned: {warned}")
# Table rows (histogram and WAV) of a band that sums negative: flagged "neg", no number after the band's centre.
listener = None
for r in table.splitlines():
    if r.startswith("listener "):
        listener = r.split()[1]
        continue
    if r.startswith("room (statistical"):  # the room's Sabine/Eyring table after the listeners'
        listener = None
        continue
    cells = r.split()
    if cells and cells[0].isdigit() and sums.get((listener, cells[0]), 1.0) < 0:
        if cells[-1] != "neg" or any(ch.isdigit() for ch in " ".join(cells[1:])):
            failures.append(f"table row of {listener} {cells[0]} Hz: {r!r}")
if negative == 0:
    failures.append("no band summed negative: the run tested nothing")
for f in failures:
    print("    " + f)
sys.exit(1 if failures else 0)
PY
  if [ $? -eq 0 ]; then passes=$((passes + 1)); else echo "FAIL: ir marks on negative-energy bands"; fails=$((fails + 1)); fi
fi
finish cli_noise_marks
