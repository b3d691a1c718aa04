// diffray.simulate, diffray.Simulation (histograms, impulse responses, metrics), diffray.convolve and
// diffray.render: the facade's and the light renderer's calls with the CLI's defaults (`diffray ir`,
// `diffray render`), the GIL released while they run; and the
// module's entry point, which translates the library's bad-input error (core::InputError) into ValueError
// with the CLI's one-line message.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <map>
#include <cmath>
#include <memory>
#include <thread>

#include "bindings.h"
#include "diffray/core/error.h"
#include "diffray/core/parallel.h"
#include "diffray/core/progress.h"
#include "diffray/diffray.h"
#include "diffray/ir/spatial_synthesis.h"
#include "diffray/ir/strength.h"
#include "diffray/ir/uncertainty.h"
#include "diffray/render/film.h"
#include "diffray/render/light_tracer.h"
#include "diffray/room/checks.h"
#include "diffray/spatial/hrtf.h"

namespace py = pybind11;

namespace diffray::python {

namespace {

/// One run: the room as it was simulated, the simulation and its seed. Immutable; Python may share it.
struct Simulation {
  room::Room room;
  transport::RoomSimulation sim;
  std::uint64_t seed = 1;
};

// A count given from Python: a whole number >= 1, or the room's default when None (the CLI's words).
std::uint64_t positiveCount(const py::object& value, const std::string& what, std::uint64_t fallback) {
  if (value.is_none()) return fallback;
  const double v = value.cast<double>();
  if (!(v >= 1.0) || v != std::floor(v) || v > 1e15)
    throw core::InputError(what, "must be a whole number >= 1 (e.g. 2000000 or 2e6)");
  return static_cast<std::uint64_t>(v);
}

// A seed from Python: a whole number in [0, 2^64 - 1], or the room's when None (the CLI's words).
std::uint64_t seedOf(const py::object& value, std::uint64_t fallback) {
  if (value.is_none()) return fallback;
  const std::string text = py::str(value);
  if (!py::isinstance<py::int_>(value) || py::isinstance<py::bool_>(value) ||
      text.find_first_not_of("0123456789") != std::string::npos)
    throw core::InputError("seed", "must be a whole number >= 0, got " + text);
  try {
    return value.cast<std::uint64_t>();
  } catch (const py::cast_error&) {
    throw core::InputError("seed", "must be at most 18446744073709551615 (2^64 - 1), got " + text);
  }
}

// Each line as a Python warning (UserWarning), as the CLI prints "diffray: warning: ..." on stderr. Raises
// what Python raises when the warnings filter turns them into errors.
void warnEach(const std::vector<std::string>& lines) {
  for (const std::string& line : lines)
    if (PyErr_WarnEx(PyExc_UserWarning, core::oneLine(line).c_str(), 1) < 0) throw py::error_already_set();
}

// Thrown from the progress callback to stop a simulation that Ctrl-C (or another signal Python raises on)
// interrupted; the Python exception is already set.
struct Interrupted {};

std::shared_ptr<Simulation> simulate(const SceneRoom& scene, const py::object& rays, const py::object& seed,
                                     const std::string& diffraction, int diffraction_order, const py::object& ism_order,
                                     double length, int threads, bool progress) {
  auto out = std::make_shared<Simulation>();
  out->room = scene.room();
  const room::Room& room = out->room;
  transport::RoomSimulationOptions so;
  so.rays = positiveCount(rays, "rays", room.output.rays);
  out->seed = seedOf(seed, room.output.seed);
  so.seed = out->seed;
  if (!ism_order.is_none()) {
    so.ism_order = ism_order.cast<int>();
    if (so.ism_order < -1 || so.ism_order > 50) throw core::InputError("ism_order", "must be in [-1, 50]");
  }
  if (!(length == 0.0 || (length >= 1e-3 && length <= 120.0)))
    throw core::InputError("length", "must be 0 (the room's) or in [0.001, 120] s");
  if (threads < 0) throw core::InputError("threads", "must be >= 0 (0: every core)");
  so.length_s = length;
  so.directions = true;  // as `diffray ir`: where the energy comes from, for the spatial IRs
  so.diffraction = diffraction;
  so.max_diffractions = diffraction_order;
  room::checkSynthesis(room, length, room.output.sample_rate_hz,
                       (room.file.empty() ? std::string("room") : room.file) + ": output.sample_rate_hz");
  warnEach(scene.warnings());
  // Python runs its signal handlers only in the main thread, with the GIL: the progress callback, when the
  // calling thread runs it (it takes its share of the work), holds the GIL for a moment and lets Python
  // check; a KeyboardInterrupt (or any exception a handler raises) then stops every thread's work.
  // At most every 50 ms, so that a busy Python thread elsewhere does not hold the tracer up at the GIL.
  std::atomic<bool> interrupted{false};
  const std::thread::id caller = std::this_thread::get_id();
  auto last_check = std::chrono::steady_clock::now();
  {
    py::gil_scoped_release release;
    core::ThreadLimit limit(threads);
    std::unique_ptr<core::Progress> bar;
    if (progress) bar = std::make_unique<core::Progress>("simulate " + room.name, so.rays * room.sources.size());
    so.on_progress = [&bar, &interrupted, &last_check, caller](std::uint64_t n) {
      if (bar) bar->add(n);
      if (interrupted.load()) throw Interrupted{};
      if (std::this_thread::get_id() != caller) return;
      const auto now = std::chrono::steady_clock::now();
      if (now - last_check < std::chrono::milliseconds(50)) return;
      last_check = now;  // only the calling thread gets here
      py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() != 0) {
        interrupted = true;
        throw Interrupted{};
      }
    };
    try {
      out->sim = transport::simulateRoom(room, so);
    } catch (const Interrupted&) {
      interrupted = true;
    }
    if (bar && !interrupted) bar->finish();
  }
  if (interrupted) throw py::error_already_set();
  warnEach(out->sim.warnings);
  return out;
}

const ir::EnergyResponse& listenerOf(const Simulation& s, long listener) {
  if (listener < 0) throw core::InputError("listener", "index " + std::to_string(listener) + " is negative");
  diffray::requireListener(s.sim, static_cast<std::size_t>(listener));
  return s.sim.listeners[static_cast<std::size_t>(listener)];
}

py::array_t<double> histogram(const Simulation& s, long listener) {
  const ir::EnergyResponse& r = listenerOf(s, listener);
  const py::ssize_t bands = r.bands.size(), bins = r.bins();
  py::array_t<double> out({bands, bins});
  auto view = out.mutable_unchecked<2>();
  for (int b = 0; b < r.bands.size(); ++b) {
    const std::vector<double> total = r.total(b);
    for (py::ssize_t k = 0; k < bins; ++k) view(b, k) = total[static_cast<std::size_t>(k)];
  }
  return out;
}

py::array_t<double> impulseResponse(const Simulation& s, long listener, const py::object& sample_rate) {
  listenerOf(s, listener);
  room::Room room = s.room;
  if (!sample_rate.is_none()) {
    room.output.sample_rate_hz = sample_rate.cast<double>();
    room::checkSynthesis(room, s.sim.length_s, room.output.sample_rate_hz, "sample_rate");
  }
  audio::AudioBuffer ir;
  {
    py::gil_scoped_release release;
    ir = diffray::impulseResponse(room, s.sim, static_cast<std::size_t>(listener), s.seed);
  }
  return py::array_t<double>(static_cast<py::ssize_t>(ir.samples.size()), ir.samples.data());
}

// The listener's spatial IR as a (channels, samples) array: AmbiX of `order`, or binaural through `hrtf`.
py::array_t<double> spatialIr(const Simulation& s, long listener, int order, const std::string* hrtf_path) {
  const ir::EnergyResponse& r = listenerOf(s, listener);
  const room::Listener& li = s.room.listeners[static_cast<std::size_t>(listener)];
  const double fs = s.room.output.sample_rate_hz;
  std::vector<std::vector<double>> channels;
  {
    py::gil_scoped_release release;
    const std::uint64_t seed = ir::listenerSeed(s.seed, static_cast<std::size_t>(listener));
    if (hrtf_path) {
      const spatial::Hrtf hrtf = spatial::Hrtf::load(*hrtf_path, fs);
      channels = ir::synthesizeBinaural(r, fs, s.sim.length_s, s.room.volume(), s.sim.speed_of_sound_m_s, seed, hrtf,
                                        li.forward, li.left, li.up);
    } else {
      channels = ir::synthesizeAmbisonic(r, fs, s.sim.length_s, s.room.volume(), s.sim.speed_of_sound_m_s, seed, order,
                                         li.forward, li.left, li.up);
    }
  }
  const auto rows = static_cast<py::ssize_t>(channels.size()), cols = static_cast<py::ssize_t>(channels.at(0).size());
  py::array_t<double> out({rows, cols});
  auto view = out.mutable_unchecked<2>();
  for (py::ssize_t c = 0; c < rows; ++c)
    for (py::ssize_t k = 0; k < cols; ++k) view(c, k) = channels[static_cast<std::size_t>(c)][static_cast<std::size_t>(k)];
  return out;
}

// The figures of `diffray ir --json`'s "bands" under Python's names (T20, ..., Ts); the other keys as they are.
py::object pythonNames(const py::object& value) {
  static const std::map<std::string, std::string> kNames{{"t20", "T20"}, {"t30", "T30"}, {"edt", "EDT"},
                                                         {"c50", "C50"}, {"c80", "C80"}, {"d50", "D50"},
                                                         {"ts", "Ts"}};
  const auto rename = [](const std::string& key) {
    const auto it = kNames.find(key);
    return it == kNames.end() ? key : it->second;
  };
  if (py::isinstance<py::dict>(value)) {
    py::dict out;
    for (const auto& item : value.cast<py::dict>())
      out[py::str(rename(item.first.cast<std::string>()))] = pythonNames(py::reinterpret_borrow<py::object>(item.second));
    return std::move(out);
  }
  if (py::isinstance<py::list>(value)) {
    py::list out;
    for (const auto& item : value.cast<py::list>())
      out.append(py::isinstance<py::str>(item) ? py::object(py::str(rename(item.cast<std::string>())))
                                               : py::reinterpret_borrow<py::object>(item));
    return std::move(out);
  }
  return value;
}

// What `diffray ir` computes per listener from the histogram: the figures, their jackknife standard errors
// and marks (ir/uncertainty.h), and its warnings on noisy or negative-energy bands (as Python warnings).
py::dict metrics(const Simulation& s, long listener) {
  const ir::EnergyResponse& response = listenerOf(s, listener);
  std::vector<ir::BandMetrics> figures = diffray::metrics(s.sim, static_cast<std::size_t>(listener));
  const std::vector<ir::BandUncertainty> marks = ir::markMetrics(figures, ir::jackknifeMetrics(response));
  warnEach(ir::uncertaintyWarnings(s.room.listeners[static_cast<std::size_t>(listener)].name, s.room.bands,
                                   figures, marks));
  nlohmann::ordered_json bands = ir::metricsJson(s.room.bands, figures);
  ir::addUncertaintyJson(bands, s.room.bands, marks);
  double power_w = 0.0;
  for (const room::Source& src : s.room.sources) power_w += src.power_w;
  ir::addStrengthJson(bands, s.room.bands, ir::strengthPerBand(response, power_w));
  const py::object loads = py::module_::import("json").attr("loads");
  py::dict out;
  for (int b = 0; b < s.room.bands.size(); ++b) {
    const double hz = s.room.bands.nominalHz(b);
    out[hz == std::floor(hz) ? py::object(py::int_(static_cast<long>(hz))) : py::object(py::float_(hz))] =
        pythonNames(loads(bands[s.room.bands.label(b)].dump()));
  }
  return out;
}

// A numpy signal as an AudioBuffer: 1-D (mono) or frames × channels.
audio::AudioBuffer buffer(const py::array_t<double, py::array::c_style | py::array::forcecast>& a, const char* what) {
  if (a.ndim() != 1 && a.ndim() != 2) throw core::InputError(what, "must be 1-D (mono) or frames × channels");
  audio::AudioBuffer out;
  out.sample_rate_hz = 1.0;  // the rate does not enter a convolution; both sides share it
  out.channels = a.ndim() == 1 ? 1 : static_cast<int>(a.shape(1));
  out.samples.assign(a.data(), a.data() + a.size());
  return out;
}

py::array_t<double> convolve(const py::array_t<double, py::array::c_style | py::array::forcecast>& dry,
                             const py::array_t<double, py::array::c_style | py::array::forcecast>& ir) {
  const audio::AudioBuffer d = buffer(dry, "dry"), h = buffer(ir, "ir");
  audio::AudioBuffer wet;
  {
    py::gil_scoped_release release;
    wet = diffray::convolve(d, h);
  }
  if (dry.ndim() == 1 && ir.ndim() == 1)
    return py::array_t<double>(static_cast<py::ssize_t>(wet.samples.size()), wet.samples.data());
  return py::array_t<double>({static_cast<py::ssize_t>(wet.frames()), static_cast<py::ssize_t>(wet.channels)},
                             wet.samples.data());
}

// What `diffray render SCENE --photons N --seed S` computes, as the linear sRGB image of its float output.
py::array_t<float> render(const std::string& path, const py::object& photons, const py::object& seed, int threads,
                          bool progress) {
  const render::LightScene scene = render::loadLightScene(path);
  render::RenderOptions options;
  options.photons = positiveCount(photons, "photons", scene.settings.photons);
  options.seed = seedOf(seed, scene.settings.seed);
  if (threads < 0) throw core::InputError("threads", "must be >= 0 (0: every core)");
  image::Image img;
  {
    py::gil_scoped_release release;
    core::ThreadLimit limit(threads);
    const auto prepared = render::prepareScene(scene, false, progress ? core::ProgressFactory(core::progressOfUnknownSize)
                                                                      : core::ProgressFactory());
    std::unique_ptr<core::Progress> bar;
    if (progress) {
      bar = std::make_unique<core::Progress>("render " + scene.name, options.photons);
      options.on_progress = [&bar](std::uint64_t n) { bar->add(n); };
    }
    const render::RenderResult r = render::renderLight(*prepared, options);
    if (bar) bar->finish();
    img = render::linearSrgb(r);
  }
  return py::array_t<float>({static_cast<py::ssize_t>(img.height), static_cast<py::ssize_t>(img.width), py::ssize_t{3}},
                            img.rgb.data());
}

}  // namespace

void bindSimulation(py::module_& m) {
  py::class_<Simulation, std::shared_ptr<Simulation>>(m, "Simulation",
      "The result of diffray.simulate: each listener's energy response (band × time), from which impulse "
      "responses and metrics are taken. Listeners are indexed as in room.listeners.")
      .def("histogram", &histogram, py::arg("listener") = 0,
           "Energy per band and time bin (J/m²) as a float64 array of shape (len(room.bands), bins); the bin "
           "width is bin_width.")
      .def("impulse_response", &impulseResponse, py::arg("listener") = 0, py::arg("sample_rate") = py::none(),
           "The listener's impulse response (float64, pressure in physical units: Σp² is energy in J/m²) at "
           "`sample_rate` Hz (default: the room's, .sample_rate); the same samples as channel `listener` of "
           "`diffray ir --seed SEED`.")
      .def("ambisonic_response",
           [](const Simulation& s, long listener, int order) { return spatialIr(s, listener, order, nullptr); },
           py::arg("listener") = 0, py::arg("order") = 1,
           "The listener's AmbiX impulse response (ACN order, SN3D; order 1-3) as a (channels, samples) array at "
           ".sample_rate, in the listener's frame; channel 0 (W) is impulse_response(listener). The samples of "
           "`diffray ir --format ambix --order ORDER --seed SEED`.")
      .def("binaural_response",
           [](const Simulation& s, long listener, const std::string& hrtf) { return spatialIr(s, listener, 0, &hrtf); },
           py::arg("listener") = 0, py::arg("hrtf") = "",
           "The listener's binaural impulse response (left, right) as a (2, samples) array at .sample_rate, "
           "through the SOFA HRTF set `hrtf` (default: Debian's MIT KEMAR set). The samples of "
           "`diffray ir --format binaural --seed SEED`.")
      .def("metrics", &metrics, py::arg("listener") = 0,
           "ISO 3382-1 figures from the listener's energy histogram, those of `diffray ir --json` (bands): "
           "{band Hz: {T20, T30, EDT (s), C50, C80 (dB), D50, Ts (s), decay_range_db, g_db (strength G), se: {figure: standard "
           "error}, flag: 'ok' | 'noisy' | 'negative_energy', noisy: [figures], not_available_negative_energy: "
           "[figures], negative_energy_fraction}}, None where a figure cannot be measured. Noisy or "
           "negative-energy bands also give a UserWarning, as the CLI warns.")
      .def_property_readonly("bin_width", [](const Simulation& s) { return s.sim.listeners.at(0).bin_s; },
                             "Histogram bin width, s.")
      .def_property_readonly("length", [](const Simulation& s) { return s.sim.length_s; }, "Simulated length, s.")
      .def_property_readonly("sample_rate", [](const Simulation& s) { return s.room.output.sample_rate_hz; },
                             "The room's sample rate (Hz), that of impulse_response by default.")
      .def_property_readonly("bands", [](const Simulation& s) {
        std::vector<double> out;
        for (int b = 0; b < s.room.bands.size(); ++b) out.push_back(s.room.bands.nominalHz(b));
        return out;
      }, "Nominal band centres, Hz (the histogram's rows).")
      .def_property_readonly("seed", [](const Simulation& s) { return s.seed; })
      .def_property_readonly("rays", [](const Simulation& s) { return s.sim.rays; }, "Rays traced in all.")
      .def_property_readonly("warnings", [](const Simulation& s) { return s.sim.warnings; });

  m.def("simulate", &simulate, py::arg("room"), py::arg("rays") = py::none(), py::arg("seed") = py::none(),
        py::arg("diffraction") = "none", py::arg("diffraction_order") = 1, py::arg("ism_order") = py::none(),
        py::arg("length") = 0.0, py::arg("threads") = 0, py::arg("progress") = true,
        R"(Traces the room: what `diffray ir ROOM` does, with the same defaults.

rays: per source (None: the room's output.rays); seed: None = the room's output.seed; the same seed gives
the same result as `diffray ir --seed`. diffraction: "none", "utd" or "wbsdf" (diffraction_order: WBSDF
scatterings per path). ism_order: image-source order (None: the room's; -1: rays only). length: IR length
in s (0: the room's, or until -60 dB). threads: 0 = every core. progress: a bar on stderr (a terminal
only). Releases the GIL while it runs; Ctrl-C stops it (KeyboardInterrupt). The scene's and the run's
warnings (the CLI's "diffray: warning: ...") are UserWarnings.)");
  m.def("render", &render, py::arg("path"), py::arg("photons") = py::none(), py::arg("seed") = py::none(),
        py::arg("threads") = 0, py::arg("progress") = true,
        "Renders a light scene (rooms/light/README.md) as `diffray render` does: the linear sRGB image (float32, "
        "height × width × 3, top row first; the CLI's .pfm/.exr before its exposure). photons, seed: None = the "
        "scene's. Releases the GIL.");
  m.def("convolve", &convolve, py::arg("dry"), py::arg("ir"),
        "The whole linear convolution of `dry` with `ir` (len(dry) + len(ir) - 1 frames), 1-D or frames × "
        "channels as diffray auralize pairs channels; single-precision FFT (within 1e-6 of the peak). "
        "Releases the GIL.");
}

}  // namespace diffray::python

PYBIND11_MODULE(_diffray, m) {
  m.doc() = R"(diffray: room acoustics by ray tracing.

    room = diffray.Room.shoebox([6, 4, 3], materials="concrete-rough")
    room.add_source([2, 2, 1.5]); room.add_listener([4, 2.5, 1.5], radius=0.3)
    sim = diffray.simulate(room, rays=20000, seed=1)
    h = sim.impulse_response(0)        # numpy, at sim.sample_rate
    sim.metrics(0)[1000]["T30"]        # seconds

load_scene reads a scene file (rooms/README.md); simulate traces it as `diffray ir` does (same seed, same
numbers); convolve auralizes a dry signal. Bad input raises ValueError with the CLI's one-line message.)";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const diffray::core::InputError& e) {
      PyErr_SetString(PyExc_ValueError, diffray::core::oneLine(e.what()).c_str());
    }
  });
  diffray::python::bindRoom(m);
  diffray::python::bindSimulation(m);
  m.attr("__all__") = py::make_tuple("Room", "Simulation", "load_scene", "material_names", "simulate", "convolve",
                                    "render");
  m.attr("__version__") = DIFFRAY_VERSION;
}
