#pragma once
// Small scenes for the UTD tests, built in code: a rigid material, box rooms and obstacles, thin plates; and
// the names the tests share (a file's own declarations of them take precedence).
#include <complex>
#include <string>

#include "diffray/room/room.h"

namespace diffray::utd {}
namespace diffray::reference {}

namespace utd_fixtures {

using diffray::core::Vec3;
using Complex = std::complex<double>;
namespace dr = diffray::room;
namespace ref = diffray::reference;
namespace utd = diffray::utd;

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kC = 343.0;  ///< speed of sound (m/s)

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
