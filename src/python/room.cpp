// diffray.Room and diffray.load_scene: rooms from scene files or built in Python (a shoebox with
// materials from the library, sources and listeners added one by one), read back as plain Python values.
#include <pybind11/stl.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "bindings.h"
#include "diffray/core/error.h"
#include "diffray/diffray.h"
#include "diffray/room/materials.h"

namespace py = pybind11;

namespace diffray::python {

namespace {

std::vector<double> xyz(const core::Vec3& v) { return {v.x(), v.y(), v.z()}; }

// A band's nominal centre as Python shows it: 1000 for octaves, 31.5 for the odd third-octave.
py::object nominal(double hz) {
  if (hz == static_cast<double>(static_cast<long>(hz))) return py::int_(static_cast<long>(hz));
  return py::float_(hz);
}

}  // namespace

SceneRoom::SceneRoom(nlohmann::json scene, std::string file, std::string base_dir)
    : scene_(std::move(scene)), file_(std::move(file)), base_dir_(std::move(base_dir)) {}

SceneRoom SceneRoom::fromFile(const std::string& path) {
  SceneRoom r;
  r.room_ = diffray::loadScene(path, &r.warnings_);
  r.parsed_ = true;
  r.file_ = path;
  r.base_dir_ = std::filesystem::path(path).parent_path().string();
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  r.scene_ = nlohmann::json::parse(text.str(), nullptr, false, true);  // comments allowed, as the loader does
  return r;
}

const room::Room& SceneRoom::room() const {
  if (!parsed_) {
    warnings_.clear();
    room_ = room::parseRoom(scene_.dump(), file_, base_dir_, &warnings_);
    parsed_ = true;
  }
  return room_;
}

void SceneRoom::append(const std::string& list, nlohmann::json entry) {
  if (!scene_.is_object()) throw core::InputError(file_, "the scene file could not be read again to edit it");
  if (!scene_.contains(list)) scene_[list] = nlohmann::json::array();
  const std::size_t n = scene_[list].size();
  const std::string prefix = list == "sources" ? "S" : "R";
  if (!entry.contains("name")) entry["name"] = prefix + std::to_string(n + 1);
  scene_[list].push_back(std::move(entry));
  parsed_ = false;
}

std::size_t SceneRoom::count(const std::string& list) const {
  if (parsed_) return list == "sources" ? room_.sources.size() : room_.listeners.size();
  return scene_.contains(list) ? scene_[list].size() : 0;
}

nlohmann::json toJson(const py::handle& object) {
  const std::string text = py::module_::import("json").attr("dumps")(object).cast<std::string>();
  return nlohmann::json::parse(text);
}

std::string packageFile(const std::string& name) {
  const auto init = py::module_::import("diffray").attr("__file__").cast<std::string>();
  return (std::filesystem::path(init).parent_path() / name).string();
}

namespace {

// Room.shoebox: a box scene in the scene-file format (rooms/README.md, "box"), materials from the
// library shipped with the package unless given inline.
SceneRoom shoebox(const std::vector<double>& dims, const py::object& materials, const py::object& absorption,
                  const py::object& scattering, const std::string& bands, const std::string& name,
                  const py::dict& output) {
  if (dims.size() != 3) throw core::InputError("shoebox", "dims must be three lengths in m (x, y, z)");
  nlohmann::json scene{{"name", name}, {"bands", bands}, {"materials_library", packageFile("materials.json")}};
  nlohmann::json box_materials;
  if (!absorption.is_none()) {
    if (!materials.is_none())
      throw core::InputError("shoebox", "give either materials or absorption (with scattering), not both");
    scene["materials"] = {{"surface", {{"absorption", toJson(absorption)}, {"scattering", toJson(scattering)}}}};
    box_materials = {{"all", "surface"}};
  } else if (py::isinstance<py::str>(materials)) {
    box_materials = {{"all", materials.cast<std::string>()}};
  } else if (py::isinstance<py::dict>(materials)) {
    box_materials = nlohmann::json::object();
    scene["materials"] = nlohmann::json::object();
    for (const auto& [key, value] : materials.cast<py::dict>()) {
      const std::string surface = py::str(key);
      scene["materials"][surface] = toJson(value);  // a library name or {"absorption": ..., "scattering": ...}
      box_materials[surface] = surface;
    }
  } else {
    throw core::InputError("shoebox", "materials must be a library name (diffray.material_names()) or a dict "
                                      "{surface: name or {absorption, scattering}}; or give absorption");
  }
  scene["geometry"] = {{{"box", {{"name", "room"}, {"min", {0, 0, 0}}, {"max", dims}, {"materials", box_materials}}}}};
  scene["sources"] = nlohmann::json::array();
  scene["listeners"] = nlohmann::json::array();
  if (!output.empty()) scene["output"] = toJson(output);
  return SceneRoom(scene, name, std::filesystem::current_path().string());
}

}  // namespace

void bindRoom(py::module_& m) {
  py::class_<SceneRoom>(m, "Room", R"(A room: geometry, materials, sources and listeners (rooms/README.md).

Made by diffray.load_scene(path) or diffray.Room.shoebox(...); sources and listeners may be added after.
The scene is checked by the same loader as the CLI's when first read (a property, simulate), so a bad
scene raises ValueError with the CLI's message.)")
      .def_static("shoebox", &shoebox, py::arg("dims"), py::arg("materials") = py::none(),
                  py::arg("absorption") = py::none(), py::arg("scattering") = 0.0, py::arg("bands") = "octave",
                  py::arg("name") = "shoebox", py::arg("output") = py::dict(),
                  R"(A box [0, dims] in m with inward walls.

materials: a library name for every surface (diffray.material_names()), or a dict keyed by "all",
  "walls", "x-", "x+", "y-", "y+", "floor", "ceiling" whose values are library names or
  {"absorption": a, "scattering": s} (a, s: one number or eight octave values 63 Hz .. 8 kHz).
absorption, scattering: one material for every surface instead (numbers or eight octave values).
bands: "octave" or "third-octave". output: the scene file's "output" fields (sample_rate_hz, rays,
  seed, ism_order, ir_length_s, max_length_s, histogram_bin_s).)")
      .def("add_source",
           [](SceneRoom& r, const std::vector<double>& position, double power_w, const std::string& directivity,
              const py::object& name) {
             nlohmann::json e{{"position", position}, {"power_w", power_w}, {"directivity", directivity}};
             if (!name.is_none()) e["name"] = name.cast<std::string>();
             r.append("sources", e);
           },
           py::arg("position"), py::arg("power_w") = 1.0, py::arg("directivity") = "omni",
           py::arg("name") = py::none(), "Adds a point source at `position` (m); named S1, S2, ... unless `name`.")
      .def("add_listener",
           [](SceneRoom& r, const std::vector<double>& position, double radius, const py::object& name,
              const py::object& look_at, double yaw, double pitch, double roll) {
             nlohmann::json e{{"position", position}, {"radius_m", radius}};
             if (!name.is_none()) e["name"] = name.cast<std::string>();
             if (!look_at.is_none()) e["look_at"] = look_at.cast<std::vector<double>>();
             if (yaw != 0.0 || pitch != 0.0 || roll != 0.0)
               e["orientation"] = {{"yaw_deg", yaw}, {"pitch_deg", pitch}, {"roll_deg", roll}};
             r.append("listeners", e);
           },
           py::arg("position"), py::arg("radius") = 0.1, py::arg("name") = py::none(), py::arg("look_at") = py::none(),
           py::arg("yaw") = 0.0, py::arg("pitch") = 0.0, py::arg("roll") = 0.0,
           "Adds a spherical listener at `position` (m) of `radius` (m); named R1, R2, ... unless `name`. It faces "
           "+x with +z up, or the point `look_at`, or turns by `yaw`, `pitch`, `roll` (degrees; the scene file's "
           "\"orientation\", rooms/README.md): the frame of its spatial responses.")
      .def_property_readonly("name", [](const SceneRoom& r) { return r.room().name; })
      .def_property_readonly("bands", [](const SceneRoom& r) {
        py::list out;
        for (int b = 0; b < r.room().bands.size(); ++b) out.append(nominal(r.room().bands.nominalHz(b)));
        return out;
      }, "Nominal band centres in Hz (the rows of a histogram, the keys of metrics).")
      .def_property_readonly("volume", [](const SceneRoom& r) { return r.room().volume(); }, "m³")
      .def_property_readonly("surface_area", [](const SceneRoom& r) { return r.room().surfaceArea(); }, "m²")
      .def_property_readonly("materials", [](const SceneRoom& r) {
        py::dict out;
        for (const auto& mat : r.room().materials)
          out[py::str(mat.name)] = py::dict(py::arg("absorption") = std::vector<double>(mat.absorption.begin(), mat.absorption.begin() + r.room().bands.size()),
                                            py::arg("scattering") = std::vector<double>(mat.scattering.begin(), mat.scattering.begin() + r.room().bands.size()));
        return out;
      }, "The room's materials: name -> {absorption, scattering} per band.")
      .def_property_readonly("sources", [](const SceneRoom& r) {
        py::list out;
        for (const auto& s : r.room().sources)
          out.append(py::dict(py::arg("name") = s.name, py::arg("position") = xyz(s.position_m),
                              py::arg("power_w") = s.power_w, py::arg("directivity") = s.directivity.pattern));
        return out;
      })
      .def_property_readonly("listeners", [](const SceneRoom& r) {
        py::list out;
        for (const auto& l : r.room().listeners)
          out.append(py::dict(py::arg("name") = l.name, py::arg("position") = xyz(l.position_m),
                              py::arg("radius") = l.radius_m, py::arg("forward") = xyz(l.forward),
                              py::arg("up") = xyz(l.up)));
        return out;
      })
      .def_property_readonly("sample_rate", [](const SceneRoom& r) { return r.room().output.sample_rate_hz; }, "Hz")
      .def_property_readonly("warnings", [](const SceneRoom& r) { r.room(); return r.warnings(); },
                             "The loader's warnings, one line each.")
      .def("__repr__", [](const SceneRoom& r) {
        return "<diffray.Room with " + std::to_string(r.count("sources")) + " sources, " +
               std::to_string(r.count("listeners")) + " listeners>";
      });

  m.def("load_scene", &SceneRoom::fromFile, py::arg("path"),
        "Reads a scene file (rooms/README.md) into a Room; ValueError with the CLI's message if it is bad.");
  m.def("material_names", [] {
    std::vector<std::string> names;
    for (const auto& [n, mat] : room::loadMaterialLibrary(packageFile("materials.json"), core::Bands::octave()))
      names.push_back(n);
    return names;
  }, "Names of the material library's entries (rooms/materials.json), usable in Room.shoebox.");
}

}  // namespace diffray::python
