#pragma once
// Shared by the spatial synthesis tests: an energy response (octave bands, 1 ms bins) holding one arrival of
// energy 1 J/m² in every band, at `delay_s` from unit direction `direction`, and no traced part.
#include "diffray/ir/response.h"

namespace diffray::test {

inline ir::EnergyResponse singleArrival(double delay_s, const core::Vec3& direction) {
  ir::EnergyResponse r;
  r.bands = core::Bands::octave();
  r.bin_s = 0.001;
  ir::Arrival a;
  a.delay_s = delay_s;
  a.energy = core::bandFill(1.0);
  a.direction = direction;
  r.arrivals.push_back(a);
  return r;
}

}  // namespace diffray::test
