#pragma once
// The statistical (diffuse-field) reverberation times of a room: Sabine's and Eyring's, per band, from its
// enclosure's surfaces, their materials' absorption and the air. They are what a diffuse field would give;
// a traced decay departs from them where the field is not diffuse (absorption on a few surfaces, little
// scattering, coupled volumes), which is why `diffray ir` prints them beside the traced figures.
// Units: m, m², m³, s. Pure functions of the room: thread-safe.
#include <vector>

#include "diffray/room/room.h"

namespace diffray::room {

struct StatisticalReverberation {
  double volume_m3 = 0.0;
  double surface_m2 = 0.0;          ///< the enclosure's area (Room::enclosure: a doorway between rooms left out)
  std::vector<double> mean_alpha;   ///< ᾱ = Σ S_i α_i / S, per band
  std::vector<double> sabine_s;     ///< per band; NaN for a room that encloses no volume
  std::vector<double> eyring_s;     ///< per band; NaN likewise
};

/// Sabine T = (24 ln10 / c)·V / (Σ S_i α_i + 4mV) and Eyring T = (24 ln10 / c)·V / (−S ln(1 − ᾱ) + 4mV)
/// (Kuttruff, Room Acoustics, 5th ed., eqs. 5.24 and 5.32 with air attenuation m, the energy attenuation
/// per metre of ISO 9613-1; reference::sabineT and eyringT), over the triangles of Room::enclosure(), c from
/// the room's air.
StatisticalReverberation statisticalReverberation(const Room& room);

}  // namespace diffray::room
