#include "diffray/transport/room_materials.h"

#include <algorithm>
#include <cmath>

namespace diffray::transport {

MaterialTable makeMaterials(const room::Room& room) {
  MaterialTable t;
  const int nb = room.bands.size();
  for (int index = 0; index < static_cast<int>(room.materials.size()); ++index) {
    const room::Material& m = room.materials[index];
    double mean_r = 0, mean_t = 0, mean_rs = 0;
    for (int b = 0; b < nb; ++b) {
      mean_r += (1.0 - m.absorption[b]) / nb;
      mean_t += m.transmission[b] / nb;
      mean_rs += (1.0 - m.absorption[b]) * m.scattering[b] / nb;
    }
    const double p_r = mean_r + mean_t > 0 ? mean_r / (mean_r + mean_t) : 1.0;
    const double p_s = mean_r > 0 ? mean_rs / mean_r : 0.0;  // reflected-energy-weighted mean scattering
    core::BandArray wt = core::bandFill(0.0), wd = core::bandFill(0.0), ws = core::bandFill(0.0);
    for (int b = 0; b < nb; ++b) {
      const double r = p_r > 0.0 ? (1.0 - m.absorption[b]) / p_r : 0.0;  // p_r = 0: nothing reflects (no 0/0)
      wt[b] = p_r < 1.0 ? m.transmission[b] / (1.0 - p_r) : 0.0;
      wd[b] = p_s > 0.0 ? r * m.scattering[b] / p_s : 0.0;
      ws[b] = p_s < 1.0 ? r * (1.0 - m.scattering[b]) / (1.0 - p_s) : 0.0;
    }
    t.p_reflect.push_back(p_r);
    t.p_diffuse.push_back(p_s);
    t.w_transmit.push_back(wt);
    t.w_diffuse.push_back(wd);
    t.w_specular.push_back(ws);
    if (nb == 8) {
      t.octave_transmit.push_back(toOctaves(wt));
      t.octave_diffuse.push_back(toOctaves(wd));
      t.octave_specular.push_back(toOctaves(ws));
    }
    t.opening.push_back(room.isOpening(index) ? 1 : 0);
    t.absorbing.push_back(mean_r + mean_t > 0 ? 0 : 1);
  }
  return t;
}

Octaves toOctaves(const core::BandArray& a) {
  Octaves o{};
  for (int b = 0; b < 4; ++b) {
    o.lo[b] = static_cast<float>(a[b]);
    o.hi[b] = static_cast<float>(a[b + 4]);
  }
  return o;
}

core::BandArray toBands(const Octaves& o) {
  core::BandArray a = core::bandFill(0.0);
  for (int b = 0; b < 8; ++b) a[b] = o[b];
  return a;
}

}  // namespace diffray::transport
