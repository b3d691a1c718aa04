#pragma once
// The render-is bench (render_is_bench.cpp): importance-sampled WBSDF shifts against
// uniform shifts at equal wall time, on the image-double-slit scene (validate/image_setup.h).
#include <cstdint>
#include <string>

namespace diffray::bench {

/// Renders the double slit with importance sampling (photons_is photons), then with uniform shifts for
/// the same wall time (photon rate from a short calibration run), and prints one JSON line: the RMS and
/// max error of each against the absolute Fraunhofer pattern (fractions of the peak), photons, seconds,
/// and (error_uniform/error_is)², the factor in photons (or time) uniform needs for IS's error.
void benchRenderIs(std::uint64_t photons_is);

/// The same comparison on a scene file (rooms/light/cd.json: a CD, Λ = 1.6 µm), which has no closed form: the
/// reference is an importance-sampled render of 8 × photons_is photons with another seed, and the errors
/// are RMS and max over every pixel's X, Y, Z against it, as fractions of the reference's peak. The
/// reference's own noise (1/√8 of the IS run's) inflates both errors a little: error_is by about 6 %.
void benchRenderIsScene(const std::string& scene_path, const std::string& name, std::uint64_t photons_is);

}  // namespace diffray::bench
