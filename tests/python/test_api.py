# The Python module's shapes, types, errors and GIL release (diffray built in CTest's tree).
import threading
import time

import numpy as np
import pytest

import diffray


def small_room():
    room = diffray.Room.shoebox([5, 4, 3], materials="concrete-rough", output={"rays": 1000})
    room.add_source([1.5, 2, 1.5])
    room.add_listener([3.5, 2.5, 1.2], radius=0.3)
    room.add_listener([4, 1, 1.5], radius=0.3)
    return room


@pytest.fixture(scope="module")
def sim():
    return diffray.simulate(small_room(), rays=2000, seed=3, length=0.3, threads=1, progress=False)


def test_room_reads_back():
    room = small_room()
    assert room.bands == [63, 125, 250, 500, 1000, 2000, 4000, 8000]
    assert room.volume == pytest.approx(60.0, rel=1e-12)
    assert room.surface_area == pytest.approx(2 * (20 + 15 + 12), rel=1e-12)
    assert [l["name"] for l in room.listeners] == ["R1", "R2"]
    assert room.listeners[0]["radius"] == 0.3
    assert "concrete-rough" in diffray.material_names()


def test_listener_orientation():
    # As the scene file's keys: the default faces +x; look_at faces the point; yaw 90 faces +y; bad ones refused.
    room = small_room()
    room.add_listener([2, 2, 1.2], look_at=[2, 3, 1.2], name="north")
    room.add_listener([2, 2, 1.2], yaw=90, pitch=30, name="turned")
    first, north, turned = room.listeners[0], room.listeners[2], room.listeners[3]
    assert first["forward"] == pytest.approx([1, 0, 0]) and first["up"] == pytest.approx([0, 0, 1])
    assert north["forward"] == pytest.approx([0, 1, 0], abs=1e-12)
    c, s = np.cos(np.radians(30)), np.sin(np.radians(30))
    assert turned["forward"] == pytest.approx([0, c, s], abs=1e-12)
    bad = small_room()
    with pytest.raises(ValueError, match="pitch_deg"):
        bad.add_listener([2, 2, 1.2], pitch=120)
        bad.listeners


def test_arrays(sim):
    h = sim.histogram(1)
    assert h.dtype == np.float64 and h.shape == (8, round(sim.length / sim.bin_width))
    ir = sim.impulse_response(0)
    assert ir.dtype == np.float64 and ir.ndim == 1 and ir.size == round(sim.length * sim.sample_rate)
    assert sim.impulse_response(0, sample_rate=32000).size == round(sim.length * 32000)
    m = sim.metrics(0)
    assert list(m) == sim.bands and set(m[1000]) >= {"T20", "T30", "EDT", "C50", "C80", "D50", "Ts"}


def test_spatial_responses(sim):
    # AmbiX: (N+1)^2 channels whose W is the omni response sample for sample; binaural: two ears of its length.
    amb = sim.ambisonic_response(0, order=2)
    ir = sim.impulse_response(0)
    assert amb.shape == (9, ir.size)
    assert np.array_equal(amb[0], ir)
    ears = sim.binaural_response(0)
    assert ears.shape == (2, ir.size) and np.all(np.isfinite(ears)) and np.any(ears[0] != ears[1])
    with pytest.raises(ValueError, match="order"):
        sim.ambisonic_response(0, order=4)
    with pytest.raises(ValueError, match="cannot read"):
        sim.binaural_response(0, hrtf="/nonexistent.sofa")


def test_unmeasurable_is_none(sim):
    # 0.3 s of a room whose T30 is over a second: the decay does not fall 35 dB (+10 past the noise).
    assert sim.metrics(0)[1000]["T30"] is None


def test_convolve_matches_numpy():
    rng = np.random.default_rng(1)
    dry, ir = rng.standard_normal(3000), rng.standard_normal(500)
    wet = diffray.convolve(dry, ir)
    ref = np.convolve(dry, ir)
    assert wet.shape == ref.shape
    # single-precision FFT: the library promises 1e-6 of the peak; float32 rounding of the inputs adds ~1e-7
    assert np.max(np.abs(wet - ref)) < 1e-5 * np.max(np.abs(ref))


def test_bad_input_raises_value_error(tmp_path, sim):
    missing = tmp_path / "missing.json"
    with pytest.raises(ValueError, match=f"^{missing}: cannot open the scene file$"):
        diffray.load_scene(str(missing))
    with pytest.raises(ValueError, match=r"^rays: must be a whole number >= 1"):
        diffray.simulate(small_room(), rays=-5)
    with pytest.raises(ValueError, match=r"^seed: must be a whole number >= 0, got -1$"):
        diffray.simulate(small_room(), rays=10, seed=-1)
    with pytest.raises(ValueError, match=r"^listener: index 2 out of range \(the room has 2 listeners\)$"):
        sim.metrics(2)
    with pytest.raises(ValueError, match="diffraction"):
        diffray.simulate(small_room(), rays=10, diffraction="magic", progress=False)
    with pytest.raises(ValueError, match="at least one source"):
        diffray.simulate(diffray.Room.shoebox([3, 3, 3], absorption=0.2), rays=10)


def test_simulate_releases_the_gil():
    # A second thread ticks every millisecond; while simulate runs (a few hundred ms on one thread) it keeps
    # ticking only if the GIL is released. Ticks are counted inside the call with 50 ms margins on each side,
    # so a tick taken just before or after the C++ part does not count.
    ticks, stop = [], threading.Event()

    def ticker():
        while not stop.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.001)

    t = threading.Thread(target=ticker)
    t.start()
    try:
        t0 = time.perf_counter()
        diffray.simulate(small_room(), rays=60000, seed=1, length=0.5, threads=1, progress=False)
        t1 = time.perf_counter()
    finally:
        stop.set()
        t.join()
    assert t1 - t0 > 0.15, "the call is too short for this check"
    assert sum(t0 + 0.05 < x < t1 - 0.05 for x in ticks) > 10
