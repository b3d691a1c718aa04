#!/usr/bin/env python3
"""The ray models against the FDTD wave reference around a door (tests/README.md, "Beyond the door at 125 Hz:
the door or the rooms?"), each scene written into a temporary folder and run through `diffray compare`:

  rooms  rooms/two-rooms.json with 24 more listeners on a grid, 20 in room B (its own two among them) and 6 in
         room A: per room and octave band (125-500 Hz), the mean and spread over the listeners of each ray
         model's G minus the wave's, how many lie within 1 dB, the difference of the spatially averaged G
         (energy mean) and the mean T30; and at three probes on the door's axis (0.8 m before it, in it,
         0.8 m behind it) G and the early energy against the wave's. --damped-b gives room B's walls, floor
         and ceiling an absorption of 0.2 (scattering 0.1): a room B whose modes overlap at 125 Hz.
  door   a 0.9 x 2.1 m door in a rigid wall (thin, or 0.2 m thick) standing in free field, no floor: a source
         3 m from the door's centre at 0, 30, 60 and 80 degrees from its normal, 20 listeners 1.5 and 3 m behind.
         Per band (63-500 Hz) the energy summed over the listeners, WBSDF (and `none`) against the wave's
         through the door: the wave's free-field calibration taken out (the same domain without the wall, wave
         minus `none`), and what the wave brings with the doorway shut (around the wall's ends) subtracted;
         "shut" is that part, dB re the open door's.

Usage: tools/door_wave_checks.py rooms [--damped-b] | door    (from the project folder, after the build)
"""
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DIFFRAY = os.path.join(ROOT, "build", "diffray")


def compare(scene, folder, models, bands):
    path = os.path.join(folder, scene["name"] + ".json")
    with open(path, "w") as f:
        json.dump(scene, f, indent=1)
    out = os.path.join(folder, scene["name"] + ".csv")
    run = subprocess.run([DIFFRAY, "compare", path, "--mode", "room", "--models", models, "--wave-bands", bands,
                          "--csv", out], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    if run.returncode != 0:
        errors = [line for line in run.stderr.splitlines() if "error" in line] or run.stderr.splitlines()[-1:]
        sys.exit(f"door_wave_checks.py: diffray compare {scene['name']} failed: " + " ".join(errors))
    figures = {}
    with open(out) as f:
        for row in csv.DictReader(f):
            for col in ("g_db", "early_db", "t30_s"):
                if row[col]:
                    figures[(row["listener"], row["model"], row["band_hz"], col)] = float(row[col])
    return figures


def energy_mean_db(values):
    return 10.0 * math.log10(sum(10.0 ** (v / 10.0) for v in values) / len(values))


def rooms(damped_b):
    with open(os.path.join(ROOT, "rooms", "two-rooms.json")) as f:
        scene = json.load(f)
    scene["name"] = "two-rooms-grid"
    # The file's own three listeners (B-in-view and B-hidden count with room B's grid) and the grid.
    scene["listeners"] += [{"name": f"B-{x}-{y}-{z}", "position": [x, y, z], "radius_m": 0.5}
                           for x in (7.0, 8.2, 9.4) for y in (0.8, 2.0, 3.2) for z in (1.2, 2.0)]
    scene["listeners"] += [{"name": f"A-{x}-{y}", "position": [x, y, 1.2], "radius_m": 0.5}
                           for x in (1.0, 3.5, 5.2) for y in (1.0, 4.0)]
    # Three probes on the door's axis at mid-height: 0.8 m before it in room A, in it, 0.8 m behind it.
    probes = {"probe-A": 5.3, "probe-door": 6.1, "probe-B": 6.9}
    scene["listeners"] += [{"name": n, "position": [x, 1.45, 1.05], "radius_m": 0.3} for n, x in probes.items()]
    if damped_b:
        scene["name"] += "-damped-b"
        scene["materials"] = {"b-damped": {"absorption": 0.2, "scattering": 0.1, "source": "a test absorber"}}
        for group in ("b-walls", "b-floor", "b-ceiling"):
            scene["geometry"][0]["obj"]["materials"][group] = "b-damped"
    models = ["none", "utd", "wbsdf"]
    with tempfile.TemporaryDirectory() as folder:
        for name in ("two-rooms.obj", "materials.json"):
            shutil.copy(os.path.join(ROOT, "rooms", name), folder)
        fig = compare(scene, folder, ",".join(models + ["wave"]), "125,250,500")
    names = [l["name"] for l in scene["listeners"]]
    for room in ("A", "B"):
        ls = [n for n in names if n.startswith(room + "-")]
        print(f"room {room}: {len(ls)} listeners; per band: model G - wave G, mean (spread) and within 1 dB; "
              "spatially averaged G difference; mean T30")
        for band in ("125", "250", "500"):
            wave = [fig[(l, "wave", band, "g_db")] for l in ls]
            cells = []
            for m in models:
                d = [fig[(l, m, band, "g_db")] - w for l, w in zip(ls, wave)]
                mean = sum(d) / len(d)
                sd = math.sqrt(sum((x - mean) ** 2 for x in d) / (len(d) - 1))
                avg = energy_mean_db([fig[(l, m, band, "g_db")] for l in ls]) - energy_mean_db(wave)
                cells.append(f"{m} {mean:+.2f} ({sd:.2f}) {sum(abs(x) <= 1.0 for x in d)}/{len(d)} avg {avg:+.2f}")
            t30 = []
            for m in models + ["wave"]:
                v = [fig[(l, m, band, "t30_s")] for l in ls if (l, m, band, "t30_s") in fig]
                t30.append(f"{m} {sum(v) / len(v):.2f} s" if v else f"{m} -")
            print(f"  {band:>4} Hz  " + " | ".join(cells) + "  || T30 " + ", ".join(t30))
    print("probes on the door's axis: model - wave, G and early energy (dB)")
    for n in probes:
        for band in ("125", "250", "500"):
            cells = [f"{m} G {fig[(n, m, band, 'g_db')] - fig[(n, 'wave', band, 'g_db')]:+.2f} early "
                     f"{fig[(n, m, band, 'early_db')] - fig[(n, 'wave', band, 'early_db')]:+.2f}" for m in models]
            print(f"  {n:10} {band:>4} Hz  " + " | ".join(cells))


def door():
    rigid = {"rigid": {"absorption": 0.0, "scattering": 0.0, "source": "ideal rigid"}}
    w, z0, z1 = 7.0, -4.0, 8.0  # the wall's half-width, foot and top (m): the wave's domain
    # Three specks that give every run the same domain, with or without the wall.
    specks = [{"polygon": {"name": f"speck{i}", "vertices": [[x, y, z], [x + 0.05, y, z], [x + 0.05, y + 0.1, z]],
                           "material": "rigid"}}
              for i, (x, y, z) in enumerate([(-5.0, w - 0.1, z1), (5.0, w - 0.1, z1), (0.0, -w, z0)])]

    def wall(d):
        if d == 0.0:
            quads = [((-w, z0), (-0.45, z1)), ((0.45, z0), (w, z1)), ((-0.45, 2.1), (0.45, z1)), ((-0.45, z0), (0.45, 0.0))]
            return [{"polygon": {"name": f"wall{i}", "material": "rigid",
                                 "vertices": [[0, y0, zz0], [0, y1, zz0], [0, y1, zz1], [0, y0, zz1]]}}
                    for i, ((y0, zz0), (y1, zz1)) in enumerate(quads)]
        return [{"box": {"name": n, "min": [-d / 2, y0, zz0], "max": [d / 2, y1, zz1], "materials": {"all": "rigid"}}}
                for n, (y0, zz0, y1, zz1) in [("left", (-w, z0, -0.45, z1)), ("right", (0.45, z0, w, z1)),
                                              ("above", (-0.45, 2.1, 0.45, z1)), ("below", (-0.45, z0, 0.45, 0.0))]]

    listeners = [{"name": f"R{x}_{y}_{z}", "position": [x, y + 0.07, z + 0.03], "radius_m": 0.3}
                 for x in (1.5, 3.0) for y in (-2.5, -1.0, 0.0, 1.0, 2.5) for z in (0.0, 2.1)]
    bands = ["63", "125", "250", "500"]

    def scene(name, geometry, angle, occluder):
        a = math.radians(angle)
        s = {"name": name, "bands": "octave", "materials": rigid, "geometry": geometry + specks,
             "sources": [{"name": "S", "position": [-3 * math.cos(a), 3 * math.sin(a), 1.05]}],
             "listeners": listeners, "air": {"temperature_c": 20, "humidity_percent": 50},
             "output": {"rays": 1000000, "seed": 1, "ir_length_s": 0.1}}
        if occluder:
            s["occluders"] = [{"type": "door", "name": "door", "centre": [0, 0, 1.05], "normal": [1, 0, 0],
                               "width_m": 0.9, "height_m": 2.1}]
        return s

    with tempfile.TemporaryDirectory() as folder:
        free = compare(scene("free", [], 0, False), folder, "none,wave", ",".join(bands))
        cal = {(l["name"], b): free[(l["name"], "wave", b, "g_db")] - free[(l["name"], "none", b, "g_db")]
               for l in listeners for b in bands}
        print("free-field calibration, wave - none (mean over listeners): " +
              " ".join(f"{b} Hz {sum(cal[(l['name'], b)] for l in listeners) / len(listeners):+.2f}" for b in bands))
        print("energy summed over the listeners behind the door, model - wave through the door (dB); bands " +
              ", ".join(bands) + " Hz")
        for thickness in (0.0, 0.2):
            # The same wall with the doorway shut: what reaches the listeners around the wall's ends (and
            # the grid's boundary returns), taken out of the wave's energy so that the door alone is compared.
            shut = wall(thickness) + [
                {"polygon": {"name": "leaf", "material": "rigid",
                             "vertices": [[0, -0.45, 0], [0, 0.45, 0], [0, 0.45, 2.1], [0, -0.45, 2.1]]}}
                if thickness == 0.0 else
                {"box": {"name": "leaf", "min": [-thickness / 2, -0.45, 0], "max": [thickness / 2, 0.45, 2.1],
                         "materials": {"all": "rigid"}}}]
            for angle in (0, 30, 60, 80):
                fig = compare(scene(f"door-{thickness}-{angle}", wall(thickness), angle, True), folder,
                              "none,wbsdf,wave", ",".join(bands))
                closed = compare(scene(f"shut-{thickness}-{angle}", shut, angle, False), folder, "none,wave",
                                 ",".join(bands))
                cells = []
                for b in bands:
                    def wave_energy(f):
                        return sum(10 ** ((f[(l["name"], "wave", b, "g_db")] - cal[(l["name"], b)]) / 10) for l in listeners)
                    opened, leak = wave_energy(fig), wave_energy(closed)
                    per = {m: sum(10 ** (fig[(l["name"], m, b, "g_db")] / 10) for l in listeners
                                  if (l["name"], m, b, "g_db") in fig) for m in ("wbsdf", "none")}
                    level = {m: f"{10 * math.log10(e / (opened - leak)):+.2f}" if e > 0.0 and opened > leak else "-"
                             for m, e in per.items()}
                    cells.append(f"wbsdf {level['wbsdf']} none {level['none']} (shut {10 * math.log10(leak / opened):+.1f})")
                print(f"  wall {'thin' if thickness == 0 else '0.2 m'}, source at {angle:2d} deg: " + " | ".join(cells))

if __name__ == "__main__":
    if sys.argv[1:] in (["-h"], ["--help"]):
        print(__doc__)
        sys.exit(0)
    if not os.access(DIFFRAY, os.X_OK):
        sys.exit(f"door_wave_checks.py: {DIFFRAY} not found: build first (tools/check or tools/quickstart)")
    if len(sys.argv) >= 2 and sys.argv[1] == "rooms" and set(sys.argv[2:]) <= {"--damped-b"}:
        rooms("--damped-b" in sys.argv[2:])
    elif sys.argv[1:] == ["door"]:
        door()
    else:
        sys.exit(__doc__)
