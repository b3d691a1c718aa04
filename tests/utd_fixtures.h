#pragma once
// Small scenes for the UTD tests, built in code: a rigid material, box rooms and obstacles, thin plates.
#include <string>

#include "diffray/room/room.h"

namespace utd_fixtures {

using diffray::core::Vec3;

inline int rigidMaterial(diffray::room::Room& room, const std::string& name = "rigid") {
  diffray::room::Material m;
  m.name = name;
  return room.addMaterial(m);
}

/// An axis-aligned box [lo, hi] (room walls or an obstacle: addBox's winding faces inwards either way).
inline void addBox(diffray::room::Room& room, const Vec3& lo, const Vec3& hi, int material) {
  const int walls[6] = {material, material, material, material, material, material};
  room.addBox(lo, hi, walls);
}

/// A rectangular thin plate: corner, and its two sides as vectors.
inline void addPlate(diffray::room::Room& room, const Vec3& corner, const Vec3& side_a, const Vec3& side_b,
                     int material) {
  room.addPolygon({corner, corner + side_a, corner + side_a + side_b, corner + side_b}, material, "plate");
}

}  // namespace utd_fixtures
