#pragma once
// Scene files (rooms/*.json, the format documented in rooms/README.md): a room's name, bands,
// materials (inline or from a material library), geometry (box rooms, planar polygons, OBJ files with
// a material per face group), sources, listeners, air and output settings, read into a room::Room.
// Every problem in the input throws one core::InputError line "FILE: FIELD.PATH: what is wrong" (or
// "FILE:LINE:COLUMN" for JSON syntax, "OBJFILE:LINE" for OBJ errors); unknown keys are errors. What
// does not stop a run (skipped zero-area faces, the geometric checks of room/checks.h: an open mesh, a
// source outside the room, …) is returned as warnings. Free functions; thread-safe.
#include <string>
#include <vector>

#include "diffray/room/room.h"

namespace diffray::room {

/// Reads a scene file. Paths inside it (materials_library, OBJ files) are relative to its folder.
/// When `warnings` is given, it receives one line per warning, the checks of roomWarnings() included.
Room loadRoom(const std::string& path, std::vector<std::string>* warnings = nullptr);

/// The same for scene text already in memory: `file` names it in messages and `base_dir` is where
/// relative paths start.
Room parseRoom(const std::string& text, const std::string& file, const std::string& base_dir,
               std::vector<std::string>* warnings = nullptr);

/// The amplitude weight a of a named first-order pattern a + (1 − a)·cos θ: omni 1, subcardioid 0.7,
/// cardioid 0.5, supercardioid 0.37, hypercardioid 0.25, dipole 0; −1 for an unknown name.
double directivityWeight(const std::string& pattern);

}  // namespace diffray::room
