#include "diffray/room/reverberation.h"

#include <cmath>
#include <limits>

#include "diffray/room/air.h"

namespace diffray::room {

StatisticalReverberation statisticalReverberation(const Room& room) {
  StatisticalReverberation out;
  const int bands = room.bands.size();
  const std::vector<char> inside = room.enclosure();
  std::vector<double> absorption_area(static_cast<std::size_t>(bands), 0.0);
  for (std::size_t i = 0; i < room.mesh.triangles.size(); ++i) {
    if (!inside[i]) continue;
    const auto& t = room.mesh.triangles[i];
    const auto& v = room.mesh.vertices;
    const double area = 0.5 * (v[t[1]] - v[t[0]]).cross(v[t[2]] - v[t[0]]).norm();
    const Material& m = room.materials[static_cast<std::size_t>(room.mesh.object_of_triangle[i])];
    out.surface_m2 += area;
    for (int b = 0; b < bands; ++b) absorption_area[static_cast<std::size_t>(b)] += area * m.absorption[static_cast<std::size_t>(b)];
  }
  out.volume_m3 = room.volume();
  const double c = speedOfSound(room.air);
  const core::BandArray air = airAttenuationPerM(room.air, room.bands);
  const double k = 24.0 * std::log(10.0) / c;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int b = 0; b < bands; ++b) {
    const double a = absorption_area[static_cast<std::size_t>(b)];
    const double alpha = out.surface_m2 > 0 ? a / out.surface_m2 : nan;
    const double air_term = 4.0 * air[static_cast<std::size_t>(b)] * out.volume_m3;
    const bool ok = out.volume_m3 > 0 && out.surface_m2 > 0;
    out.mean_alpha.push_back(alpha);
    out.sabine_s.push_back(ok ? k * out.volume_m3 / (a + air_term) : nan);
    out.eyring_s.push_back(ok && alpha < 1.0 ? k * out.volume_m3 / (-out.surface_m2 * std::log1p(-alpha) + air_term)
                                             : (ok ? 0.0 : nan));
  }
  return out;
}

}  // namespace diffray::room
