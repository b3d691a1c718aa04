#pragma once
// The BTM edge-diffraction reference (reference/btm_spectrum.h) as compare's exact point model, for the
// scenes it fits: one rigid `barrier` (its panel a thin rigid plate with every edge diffracting) standing in
// free field (no other geometry) or on a rigid ground (every other triangle in the horizontal plane of the
// panel's foot, absorption 0 in every band: the image principle's infinite rigid plane). Second order in
// edge diffraction.
//
// Size limit: the second order's cost grows as the square of the plate's perimeter in wavelengths, so the
// reference is given up to the frequency at which that perimeter (with the ground, the plate joined with its
// mirror image) is kBtmMaxPerimeterWavelengths wavelengths; above it the model returns NaN (no value, as
// for a band that has none), and the assumption line says where it stops.
// Thread-safety: the model is immutable after construction; relativePressure may be called concurrently.
#include <memory>
#include <string>

#include "diffray/compare/point_models.h"

namespace diffray::compare {

/// The perimeter, in wavelengths, up to which the BTM reference is computed. On rooms/screen.json (limit
/// 6435 Hz) one point of a listener's ball rule, every band at once, takes about 1.7 s on 2 cores.
inline constexpr double kBtmMaxPerimeterWavelengths = 300.0;

/// The BTM model if `room` fits it (see above), else null and `why_not` says why. `assumption` describes
/// the reference for the table's header.
std::unique_ptr<PointModel> btmModelFor(const room::Room& room, double speed_of_sound_m_s, std::string& why_not,
                                        std::string& assumption);

}  // namespace diffray::compare
