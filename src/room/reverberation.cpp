#include "diffray/room/reverberation.h"

#include <algorithm>
#include <limits>

#include "diffray/reference/room_acoustics.h"
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
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const bool closed = out.volume_m3 > 0 && out.surface_m2 > 0;
  for (int b = 0; b < bands; ++b) {
    const double a = absorption_area[static_cast<std::size_t>(b)], m = air[static_cast<std::size_t>(b)];
    const double alpha = out.surface_m2 > 0 ? a / out.surface_m2 : nan;
    const bool decays = closed && a + 4.0 * m * out.volume_m3 > 0;  // else the formulas' decay never ends
    out.mean_alpha.push_back(alpha);
    out.sabine_s.push_back(decays ? reference::sabineT(out.volume_m3, a, m, c) : nan);
    out.eyring_s.push_back(decays ? reference::eyringT(out.volume_m3, out.surface_m2, std::min(alpha, 1.0), m, c) : nan);
  }
  return out;
}

}  // namespace diffray::room
