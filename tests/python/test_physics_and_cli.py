# The Python module against the CLI (same scene and seed: the same numbers) and against Eyring's formula.
import json
import math
import pathlib
import subprocess

import numpy as np
import pytest

import diffray

SCENE = {
    "name": "pybox",
    "bands": "octave",
    "materials": {"walls": {"absorption": 0.1, "scattering": 1.0}},
    "geometry": [{"box": {"name": "room", "min": [0, 0, 0], "max": [6, 4, 3], "materials": {"all": "walls"}}}],
    "sources": [{"name": "S1", "position": [1.5, 2.0, 1.5]}],
    "listeners": [{"name": "R1", "position": [4.2, 2.6, 1.3], "radius_m": 0.4},
                  {"name": "R2", "position": [5.0, 1.0, 1.6], "radius_m": 0.4}],
    "output": {"sample_rate_hz": 24000, "ir_length_s": 1.5, "rays": 4000, "seed": 5},
}


def float_wav(path):
    """The samples of a 32-bit float WAV as frames x channels (RIFF chunks read by hand)."""
    data = path.read_bytes()
    pos, channels = 12, None
    while pos < len(data):
        tag, size = data[pos:pos + 4], int.from_bytes(data[pos + 4:pos + 8], "little")
        body = data[pos + 8:pos + 8 + size]
        if tag == b"fmt ":
            channels = int.from_bytes(body[2:4], "little")
        elif tag == b"data":
            return np.frombuffer(body, dtype="<f4").reshape(-1, channels)
        pos += 8 + size + (size & 1)
    raise AssertionError("no data chunk")


def test_same_numbers_as_the_cli(tmp_path, cli):
    scene = tmp_path / "pybox.json"
    scene.write_text(json.dumps(SCENE))
    wav = tmp_path / "out.wav"
    run = subprocess.run([cli, "ir", str(scene), "--seed", "11", "--rays", "3000", "--json", "-o", str(wav)],
                         capture_output=True, text=True, check=True)
    side = json.loads(run.stdout)
    sim = diffray.simulate(diffray.load_scene(str(scene)), rays=3000, seed=11, progress=False)
    samples = float_wav(wav)
    for index, listener in enumerate(side["listeners"]):
        mine = sim.metrics(index)
        for band, figures in listener["bands"].items():
            for key, name in [("t20", "T20"), ("t30", "T30"), ("edt", "EDT"), ("c50", "C50"), ("c80", "C80"),
                              ("d50", "D50"), ("ts", "Ts")]:
                assert mine[int(band)][name] == figures[key], (index, band, key)
            # the range, the standard errors and the marks of the JSON, under Python's names
            assert mine[int(band)]["decay_range_db"] == figures["decay_range_db"], (index, band)
            assert mine[int(band)]["g_db"] == figures["g_db"], (index, band)
            names = dict(t20="T20", t30="T30", edt="EDT", c50="C50", c80="C80", d50="D50", ts="Ts")
            assert mine[int(band)]["se"] == {names.get(k, k): v for k, v in figures["se"].items()}, (index, band)
            assert mine[int(band)]["flag"] == figures["flag"], (index, band)
            assert mine[int(band)].get("noisy", []) == [names[k] for k in figures.get("noisy", [])], (index, band)
        # the WAV holds float32: the Python samples rounded to float32 are the same bits
        ir = sim.impulse_response(index)
        assert np.array_equal(ir.astype(np.float32), samples[:, index])
    # the defaults (rays, seed from the file) are the CLI's too
    default = subprocess.run([cli, "ir", str(scene), "--json", "-o", str(wav)], capture_output=True, text=True,
                             check=True)
    first = json.loads(default.stdout)["listeners"][0]["bands"]["1000"]["t30"]
    assert diffray.simulate(diffray.load_scene(str(scene)), progress=False).metrics(0)[1000]["T30"] == first


def test_t30_matches_eyring():
    # Oracle: Eyring, T = 24 ln10 V / (c (-S ln(1 - a) + 4 m V)), for a 6 x 4 x 3 m box with a = 0.1 on
    # every wall and fully diffuse (Lambert) reflection, at 500 Hz. Tolerance 5 %, from three terms:
    # - Eyring neglects the spread of free path lengths; Kuttruff (Room Acoustics, 5th ed., eq. 5.46) gives
    #   the decay rate -ln(1-a) - (g2/2) ln^2(1-a) with g2 ~ 0.4 for boxes: T about 2 % longer at a = 0.1;
    # - air absorption (ISO 9613-1) at 500 Hz, 20 C, 50 %: m ~ 6e-4 Np/m, 4 m V ~ 0.17 m^2 against
    #   -S ln(1 - a) = 11.4 m^2: about 1.5 %, left out of the formula below;
    # - Monte Carlo: 20000 rays, T30 fitted over 30 dB of a ~1 s decay: standard error under 1 %.
    dims, a = (6.0, 4.0, 3.0), 0.1
    room = diffray.Room.shoebox(list(dims), absorption=a, scattering=1.0, output={"ir_length_s": 1.5})
    room.add_source([1.5, 2.0, 1.5])
    room.add_listener([4.2, 2.6, 1.3], radius=0.4)
    sim = diffray.simulate(room, rays=20000, seed=2, progress=False)
    v = dims[0] * dims[1] * dims[2]
    s = 2 * (dims[0] * dims[1] + dims[0] * dims[2] + dims[1] * dims[2])
    c = 331.3 * math.sqrt(1 + 20 / 273.15)
    eyring = 24 * math.log(10) * v / (c * -s * math.log(1 - a))
    assert sim.metrics(0)[500]["T30"] == pytest.approx(eyring, rel=0.05)


def test_render_is_the_cli_float_image(tmp_path, cli):
    # The Python image equals the CLI's PFM (little-endian, rows bottom-up) bit for bit, same photons and seed.
    scene = str(pathlib.Path(__file__).parents[2] / "rooms" / "light" / "laser-aperture.json")
    png = tmp_path / "la.png"
    subprocess.run([cli, "render", scene, "--photons", "20000", "--seed", "3", "-o", str(png)],
                   capture_output=True, check=True)
    data = (tmp_path / "la.pfm").read_bytes()
    header = data.split(b"\n", 3)
    width, height = map(int, header[1].split())
    assert header[0] == b"PF" and float(header[2]) < 0
    pfm = np.frombuffer(header[3], dtype="<f4").reshape(height, width, 3)[::-1]
    img = diffray.render(scene, photons=20000, seed=3, progress=False)
    assert img.dtype == np.float32 and img.shape == (height, width, 3)
    assert np.array_equal(img, pfm) and np.any(img > 0)
