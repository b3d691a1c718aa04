// The Python module's entry point: the module docstring, the binders and the translation of the
// library's bad-input error (core::InputError) into ValueError with the CLI's one-line message.
#include "bindings.h"
#include "diffray/core/error.h"

namespace py = pybind11;

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
  m.attr("__all__") = py::make_tuple("Room", "Simulation", "load_scene", "material_names", "simulate", "convolve");
  m.attr("__version__") = DIFFRAY_VERSION;
}
