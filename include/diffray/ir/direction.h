#pragma once
// Where the early sound of a band comes from, read from an EnergyResponse that recorded directions
// (transport::RoomSimulationOptions::directions): the energy vector of Gerzon (1992, "General
// metatheory of auditory localisation", AES 92nd Convention, preprint 3306), r_E = Σ e·u / Σ e over the
// window, u the unit vector towards each contribution. Its direction is where the energy comes from on
// balance; its length r_E is 1 when everything arrives from one direction and tends to 0 in a diffuse field.
// The window starts at the band's onset (ir::onsetBin: 20 dB below the peak bin, ISO 3382-1 A.3.4) and
// spans window_s: 10 ms by default, the span over which the first wavefront dominates where a sound is
// heard to come from (the precedence effect; Litovsky et al., J. Acoust. Soc. Am. 106, 1999). Directions
// are given in the listener's frame: x forward, y left, z up; azimuth atan2(y, x) in degrees (positive to
// the left), elevation asin(z/|r|) (positive up). Pure functions; thread-safe.
#include <limits>

#include "diffray/core/math.h"
#include "diffray/ir/response.h"

namespace diffray::ir {

struct EarlyDirection {
  double energy = 0.0;  ///< the window's energy, J/m² (arrivals and traced part)
  double azimuth_deg = std::numeric_limits<double>::quiet_NaN();
  double elevation_deg = std::numeric_limits<double>::quiet_NaN();
  double r_e = std::numeric_limits<double>::quiet_NaN();  ///< |Σ e·u| / Σ e; NaN without positive energy
  core::Vec3 world{0, 0, 0};                              ///< the unit direction in world coordinates
};

/// The energy vector of band `band` over [onset, onset + window_s), in the frame (forward, left, up).
/// NaN figures when the band has no positive energy or the response recorded no directions (its traced part
/// then counts as arriving from nowhere: only its arrivals' directions are used, and `energy` still counts
/// everything).
EarlyDirection earlyDirection(const EnergyResponse& response, int band, const core::Vec3& forward,
                              const core::Vec3& left, const core::Vec3& up, double window_s = 0.010);

}  // namespace diffray::ir
