#pragma once
// The signed-energy ray tracer (Cuypers et al. 2012). Rays leave a source with a wavelength and an energy,
// are intersected with the scene (Embree), and at each occluder draw a shift (u', v') from its WBSDF
// (paper eq. 8, angle-shift invariance: u_o = u_i + u'); the sign of W travels in the ray's energy.
// Outgoing direction (λu_o, λv_o, ±√(1 − λ²(u_o² + v_o²))); an imaginary root is an evanescent wave:
// the ray ends and its energy is tallied. Screens record and absorb rays; spheres record the rays that
// pass through them and let them go on.
// Deterministic: the same seed gives identical tallies for any thread count (core/parallel.h).
#include <cstdint>
#include <functional>
#include <vector>

#include "diffray/receiver/screen.h"
#include "diffray/transport/scene.h"

namespace diffray::transport {

struct TraceOptions {
  std::uint64_t rays = 1'000'000;
  std::uint64_t seed = 1;
  int max_bounces = 32;
  std::uint64_t chunk_rays = 16384;
  /// Randomised quasi-Monte Carlo for the source position and the first WBSDF draw (core/rng.h);
  /// false = plain Monte Carlo. Both are unbiased.
  bool qmc = true;
  std::function<void(std::uint64_t)> on_progress;  ///< called with rays done per chunk (thread-safe)
};

/// Signed energies (in the source's power units) of every fate a ray can meet.
struct TraceResult {
  std::vector<receiver::ScreenTally> screens;
  std::vector<receiver::ScreenTally> spheres;  ///< one bin each: the energy of every crossing
  receiver::ScreenTally far_field;              ///< escaping rays by direction (Scene::setFarField)
  double emitted = 0, absorbed = 0, evanescent = 0, escaped = 0, on_absorbers = 0, bounce_limit = 0;
  std::uint64_t rays = 0;
  std::uint64_t segments = 0;  ///< intersection queries made
  void merge(const TraceResult& o);
};

TraceResult trace(const Scene& scene, const CollimatedSource& source, const TraceOptions& options);

/// One WBSDF scattering at an occluder (paper eq. 8–10): shifts (u', v') drawn from the occluder's tables at
/// its local (x, y) with the uniforms xi_x, xi_y; `dir` (unit, world) is replaced by the outgoing direction
/// (λ(u_i + u'), λ(v_i + v'), ±√(1 − …)) (less x/f, y/f for a lens: Occluder::focal_length_m), mirrored for
/// reflecting occluders. `weight` is the signed factor
/// on the ray's energy (0 where t = 0). Shared by trace() and the light tracer (render/light_tracer.h).
/// `uniform_shifts`: draw u' uniformly over the tables' ranges (WbsdfTable::sampleUniform) instead of by
/// |W|: unbiased, noisier; for the render-is bench.
enum class ScatterFate { Continue, Absorbed, Evanescent };
ScatterFate scatterAtOccluder(const Occluder& occ, const geometry::Frame& frame, double x_m, double y_m,
                              double wavelength_m, double xi_x, double xi_y, double* dir, double& weight,
                              bool uniform_shifts = false);

}  // namespace diffray::transport
