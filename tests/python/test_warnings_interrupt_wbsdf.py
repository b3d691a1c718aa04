# The Python module's warnings (the CLI's "diffray: warning: ..." lines as UserWarning), Ctrl-C during a
# long simulate (KeyboardInterrupt), and diffraction="wbsdf" against `diffray ir --diffraction wbsdf`.
import json
import os
import pathlib
import signal
import subprocess
import threading

import numpy as np
import pytest

import diffray
from test_physics_and_cli import float_wav

ROOMS = pathlib.Path(__file__).resolve().parents[2] / "rooms"


def far_listener_room():
    room = diffray.Room.shoebox([8, 5, 3], materials="concrete-rough")
    room.add_source([1, 2.5, 1.5])
    room.add_listener([7, 2.5, 1.5], radius=0.05)  # small and far: few rays cross it
    return room


def test_run_warnings_are_user_warnings():
    with pytest.warns(UserWarning, match="ray segments only"):
        diffray.simulate(far_listener_room(), rays=300, seed=1, length=0.2, progress=False)


def test_noisy_bands_warn_and_are_flagged():
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        sim = diffray.simulate(diffray.load_scene(str(ROOMS / "shoebox.json")), rays=5000, seed=1, progress=False)
    with pytest.warns(UserWarning, match=r"listener R1, \d+ Hz: .* exceeds its JND"):
        m = sim.metrics(0)
    flagged = [hz for hz, band in m.items() if band["flag"] == "noisy"]
    assert flagged
    for hz in flagged:
        assert m[hz]["noisy"], hz
        for name in m[hz]["noisy"]:
            assert m[hz]["se"][name] is not None and m[hz][name] is not None, (hz, name)


def test_warnings_can_be_made_errors():
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        with pytest.raises(UserWarning, match="ray segments only"):
            diffray.simulate(far_listener_room(), rays=300, seed=1, length=0.2, progress=False)


def test_ctrl_c_interrupts_a_long_simulate():
    room = diffray.load_scene(str(ROOMS / "shoebox.json"))
    timer = threading.Timer(0.5, lambda: os.kill(os.getpid(), signal.SIGINT))
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            diffray.simulate(room, rays=20_000_000, progress=False)  # minutes of work, were it not stopped
    finally:
        timer.cancel()
    # the module still works afterwards
    with pytest.warns(UserWarning, match="ray segments only"):  # 500 rays: the CLI warns too
        assert diffray.simulate(room, rays=500, seed=2, length=0.1, progress=False).rays == 500


def test_wbsdf_is_the_cli_for_the_same_seed(tmp_path, cli):
    wav = tmp_path / "two.wav"
    run = subprocess.run([cli, "ir", str(ROOMS / "two-rooms.json"), "--diffraction", "wbsdf", "--rays", "3000",
                          "--seed", "9", "--json", "-o", str(wav)], capture_output=True, text=True, check=True)
    side = json.loads(run.stdout)
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # few rays: noisy bands, as the CLI warns
        sim = diffray.simulate(diffray.load_scene(str(ROOMS / "two-rooms.json")), rays=3000, seed=9,
                               diffraction="wbsdf", progress=False)
        samples = float_wav(wav)
        for index, listener in enumerate(side["listeners"]):
            mine = sim.metrics(index)
            for band, figures in listener["bands"].items():
                for key, name in [("t20", "T20"), ("t30", "T30"), ("edt", "EDT"), ("c50", "C50"),
                                  ("c80", "C80"), ("d50", "D50"), ("ts", "Ts")]:
                    assert mine[int(band)][name] == figures[key], (index, band, key)
                assert mine[int(band)]["flag"] == figures["flag"], (index, band)
                assert mine[int(band)]["negative_energy_fraction"] == figures["negative_energy_fraction"]
            assert np.array_equal(sim.impulse_response(index).astype(np.float32), samples[:, index])
