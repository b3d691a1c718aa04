#pragma once
// Shared pieces of the Python module `diffray` (src/python/README.md): the scene a Python Room holds and
// the binders of each part. Conversions only: every computation is a library call (diffray/diffray.h).
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "diffray/room/room.h"

namespace diffray::python {

/// A room as Python sees it: a scene (the scene-file format, rooms/README.md) that may still be edited
/// (add_source, add_listener), parsed by the library's scene loader when it is first read, so that a room
/// built in Python is checked exactly as a scene file is, with the same messages. `file` names the scene
/// in messages; `base_dir` is where its relative paths (materials_library, OBJ meshes) start.
/// Not thread-safe (Python holds the GIL while touching it).
class SceneRoom {
 public:
  /// A scene file, read by room::loadRoom (its messages) and kept as text for later edits.
  static SceneRoom fromFile(const std::string& path);
  /// A scene built in code (not parsed until read).
  SceneRoom(nlohmann::json scene, std::string file, std::string base_dir);

  /// The parsed room; throws core::InputError for a bad scene (no source yet, a listener outside, ...).
  const room::Room& room() const;
  const std::vector<std::string>& warnings() const { return warnings_; }
  /// Appends an entry to the scene's "sources" or "listeners" list (checked when next parsed).
  void append(const std::string& list, nlohmann::json entry);
  std::size_t count(const std::string& list) const;

 private:
  SceneRoom() = default;
  nlohmann::json scene_;
  std::string file_, base_dir_;
  mutable bool parsed_ = false;
  mutable room::Room room_;
  mutable std::vector<std::string> warnings_;
};

/// A Python object (dict, list, number, string) as JSON, through Python's json module.
nlohmann::json toJson(const pybind11::handle& object);

/// The path of a file shipped inside the package folder (materials.json).
std::string packageFile(const std::string& name);

void bindRoom(pybind11::module_& m);
void bindSimulation(pybind11::module_& m);

}  // namespace diffray::python
