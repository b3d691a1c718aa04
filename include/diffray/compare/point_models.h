#pragma once
// The models of a comparison that give a complex pressure at a point: UTD
// (utd/paths.h) on the scene's own mesh, and the exact reference that fits the scene, if one does
// (reference/half_plane_point.h for one free edge or barrier, reference/aperture_point.h for one door or
// slit in a plane screen). Both return the field of a unit point source relative to its free field at the
// same distance, |p·R|² (so 0 dB is free field), at one frequency, or averaged over a band on a uniform
// frequency grid and over the listener's sphere (a 6-point degree-3 ball rule: the WBSDF model scores the
// fluence through the sphere, so the point models are read the same way). Thread-safe after construction.
#include <complex>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "diffray/core/math.h"
#include "diffray/room/room.h"

namespace diffray::compare {

class PointModel {
 public:
  virtual ~PointModel() = default;
  virtual std::string name() const = 0;
  /// |p(f)·R|² at `listener` for the source at `source`, for each frequency in `freqs_hz`: |relativePressure|²
  /// unless the model adds arrivals as energies.
  virtual std::vector<double> relativeEnergy(const core::Vec3& source, const core::Vec3& listener,
                                             const std::vector<double>& freqs_hz) const;
  /// p(f)/p_free(f) = p·R·e^{ikR} (time factor e^{iωt}, p_free = e^{−ikR}/R): magnitude and phase re the
  /// free field at the same distance, for each frequency. NaN where the model has no phase (a reference
  /// that adds two arrivals as energies).
  virtual std::vector<std::complex<double>> relativePressure(const core::Vec3& source, const core::Vec3& listener,
                                                             const std::vector<double>& freqs_hz) const = 0;
  /// Whether the model adds arrivals as energies (it has no phase: relativePressure is NaN, relativeEnergy
  /// holds the levels). Otherwise a NaN pressure is a frequency the model gives no value at.
  virtual bool addsEnergies() const { return false; }
};

/// The exact reference for `room` if its occluders fit one (else null, with the reason in `why_not`). The
/// room's other geometry is ignored by the reference (a half-plane is infinite; an aperture's screen is
/// the infinite plane of the door, black, on an optional rigid floor): `assumption` says which, for callers
/// to print next to the numbers.
/// `incoherent_floor`: for a door on a floor, the direct and floor-reflected arrivals add as energies (the
/// reference an energy ray tracer such as the WBSDF model can match: it cannot produce the coherent ground
/// interference between two different paths, which UTD and the coherent reference do).
std::unique_ptr<PointModel> exactModelFor(const room::Room& room, double speed_of_sound_m_s, std::string& why_not,
                                          std::string& assumption, bool incoherent_floor = false);

/// UTD on the room's mesh (first- and second-order diffraction, each with every combination of first-order
/// reflections around its edges, direct and first-order reflections, face reflection from the materials).
std::unique_ptr<PointModel> utdModelFor(const room::Room& room, double speed_of_sound_m_s);

/// Band average of relativeEnergy over `points` uniform frequencies in [lo, hi] and over the 6-point ball
/// rule of radius `radius_m` around `listener`, relative to the free field at the ball's centre.
double bandRelativeEnergy(const PointModel& m, const core::Vec3& source, const core::Vec3& listener, double radius_m,
                          double lo_hz, double hi_hz, int points);
/// The same for several bands (lo, hi) at once: one relativeEnergy call per point of the ball rule with every
/// band's frequencies (a model that prepares per call, as the BTM reference does, prepares once per point);
/// each band's sum in the same order as bandRelativeEnergy's.
std::vector<double> bandRelativeEnergies(const PointModel& m, const core::Vec3& source, const core::Vec3& listener,
                                         double radius_m, const std::vector<std::pair<double, double>>& bands_hz,
                                         int points);

}  // namespace diffray::compare
