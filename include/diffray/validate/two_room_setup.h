#pragma once
// Scenes of the wave validation cases (wave_cases.cpp): two box rooms joined through a partition by an
// open door on the floor, built in code from case parameters. Room A is [0, a]³ from the origin; the
// partition of thickness `wall_m` follows A's far face along the join axis (x or y); room B starts behind
// it, shifted along the lateral (other horizontal) axis by `b_offset_m`. The door spans [door_pos_m,
// door_pos_m + door_width_m] laterally and [0, door_height_m] in height; its opening rectangle, a WBSDF
// door with sill "floor" and Kirchhoff faces (as rooms/*.json declare it), lies in the partition's
// mid-plane. The surfaces are the air/solid faces of a rectilinear cell grid (as tools/make_rooms.py
// generates rooms/two-rooms.obj and rooms/classroom.obj), so the mesh is closed with shared vertices.
// Octave bands 63 Hz–8 kHz, air 20 °C / 50 %. Units: metres. Pure functions.
#include <array>
#include <string>
#include <vector>

#include "diffray/room/room.h"
#include "diffray/validate/case.h"

namespace diffray::validate {

/// The surface groups that carry a material, in the order of TwoRoomSpec::absorption.
enum TwoRoomSurface { kAFloor, kACeiling, kASideLo, kASideHi, kAFar, kAPartition, kBFloor, kBCeiling, kBWalls, kReveal, kTwoRoomSurfaces };

struct TwoRoomSpec {
  int axis = 0;  ///< the join axis: 0 = x, 1 = y
  std::array<double, 3> dims_a_m{6, 5, 3}, dims_b_m{4, 4, 3};  ///< world x y z sizes
  double b_offset_m = 0.0;  ///< room B's lateral start
  double wall_m = 0.2;
  double door_width_m = 0.9, door_height_m = 2.1, door_pos_m = 1.0;
  std::array<double, 3> source_m{2, 2.5, 1.5};
  std::vector<std::array<double, 3>> listeners_m;
  std::vector<std::string> listener_names;
  double radius_m = 0.5;
  /// Per surface (TwoRoomSurface), 8 octave-band absorption coefficients (63 Hz–8 kHz).
  std::array<std::vector<double>, kTwoRoomSurfaces> absorption;
  double scattering = 0.05;
};

/// The ParamSpecs of a two-room case; `defaults` holds the default geometry and absorptions.
std::vector<ParamSpec> twoRoomParams(const TwoRoomSpec& defaults);
/// Reads the parameters (names as twoRoomParams gives them) into a spec with `axis` and listener names
/// taken from `base`. Throws core::InputError (one line) when the door does not fit in the shared wall, a
/// source or listener sphere is outside both rooms, or a list has the wrong length.
TwoRoomSpec twoRoomFromParams(const Params& p, const TwoRoomSpec& base);
room::Room makeTwoRooms(const TwoRoomSpec& spec);
/// Whether listener `l` is hidden from the source: behind the partition's mid-plane, and the straight
/// line from the source does not cross that plane inside the door.
bool hiddenFromSource(const TwoRoomSpec& spec, std::size_t l);

}  // namespace diffray::validate
