#pragma once
// Small scenes for the UTD tests, built in code: a rigid material, box rooms and obstacles, thin plates; and
// the names the tests share (a file's own declarations of them take precedence); octave bands of UTD against
// the BTM reference.
#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "diffray/reference/btm_field.h"
#include "diffray/room/room.h"
#include "diffray/utd/paths.h"

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

/// `points` frequencies in each octave band of `centres_hz` at the midpoints of equal parts of [c/√2, c·√2],
/// band after band.
inline std::vector<double> octaveGrid(const std::vector<double>& centres_hz, int points) {
  std::vector<double> f;
  for (double band : centres_hz)
    for (int j = 0; j < points; ++j) {
      const double lo = band / std::sqrt(2.0), hi = band * std::sqrt(2.0);
      f.push_back(lo + (j + 0.5) * (hi - lo) / points);
    }
  return f;
}

/// Per band of octaveGrid(…, points): 10·log10 of Σ|UTD|² over Σ|BTM|² on the band's frequencies, UTD the
/// sum of `paths` at f[i], BTM exact[i].total().
inline std::vector<double> utdMinusBtmDb(const utd::UtdModel& model, const std::vector<utd::Path>& paths,
                                         const std::vector<double>& f, const std::vector<ref::BtmField>& exact,
                                         int points) {
  std::vector<double> out;
  for (std::size_t b = 0; b * static_cast<std::size_t>(points) < f.size(); ++b) {
    double e_utd = 0.0, e_btm = 0.0;
    for (int j = 0; j < points; ++j) {
      const std::size_t i = b * static_cast<std::size_t>(points) + static_cast<std::size_t>(j);
      e_utd += std::norm(model.total(paths, f[i], kC));
      e_btm += std::norm(exact[i].total());
    }
    out.push_back(10.0 * std::log10(e_utd / e_btm));
  }
  return out;
}

}  // namespace utd_fixtures
