#pragma once
// The BTM edge-diffraction reference (reference/btm_spectrum.h, reference/btm_box.h) as compare's exact
// point model, for the scenes it fits: one rigid `barrier` (its panel a thin rigid plate with every edge diffracting) standing in
// free field (no other geometry) or on a rigid ground (every other triangle in the horizontal plane of the
// panel's foot, absorption 0 in every band: the image principle's infinite rigid plane). Second order in
// edge diffraction. Or, with no occluders, one rigid axis-aligned box (a cupboard: the `box` geometry, or
// triangles covering its faces) standing in free field (its bottom face the scene's only other surface) or
// on a rigid ground (the triangles in the plane of its bottom reach beyond it).
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
/// 6435 Hz) one point of a listener's ball rule, every band at once, takes about 1.1 s on 2 idle cores.
inline constexpr double kBtmMaxPerimeterWavelengths = 300.0;

/// The same limit for a box: the total length of its edges (with the ground, of the box joined with its
/// mirror image), in wavelengths. A 1.2 × 0.6 × 1.8 m box on a ground (21.6 m of edges) is given up to
/// 5720 Hz, above the 4 kHz octave band's upper edge (5657 Hz).
inline constexpr double kBtmMaxBoxEdgeWavelengths = 360.0;

/// The BTM model if `room` fits it (see above), else null and `why_not` says why. `assumption` describes
/// the reference for the table's header.
std::unique_ptr<PointModel> btmModelFor(const room::Room& room, double speed_of_sound_m_s, std::string& why_not,
                                        std::string& assumption);

/// The BTM model of one rigid box (see above) if `room` fits it, else null and `why_not` says why. Throws
/// core::InputError when a source lies inside or on the box or a listener's sphere meets it.
std::unique_ptr<PointModel> btmBoxModelFor(const room::Room& room, double speed_of_sound_m_s, std::string& why_not,
                                           std::string& assumption);

}  // namespace diffray::compare
