#pragma once
// The acoustic ray tracer. A ray leaves a point source in a direction drawn uniformly
// on the sphere, weighted by the source's normalised power pattern, and carries one energy per band at
// once (core::BandArray; with eight bands, Octaves: floats relative to the emitted level). At a surface it is reflected or transmitted with probabilities proportional to
// the band-mean reflected (1 − α) and transmitted (τ) fractions; a reflection is Lambert (cosine lobe)
// with the band-mean scattering probability, else specular; the band energies are reweighted by the
// per-band ratio, so every band stays unbiased while the ray stays one ray (a WBSDF occluder
// sends each band its own way: RoomTraceOptions::occluders). Air absorption e^{−m·d} per band (ISO 9613-1) is applied at scoring,
// from the path length d; Russian roulette below `roulette_level` of the emitted energy keeps the
// estimator unbiased. Listener spheres score the track length inside them (receiver/sphere.h) into band ×
// time histograms, time = path length / c.
// Paths made only of specular reflections (no transmission, no diffuse bounce) of order ≤ skip_order are
// NOT scored: the image-source method (transport/image_sources.h) adds them exactly, so nothing is counted
// twice. Units: metres, seconds, energy as fluence J/m² (a 1 W omni source gives 1/r² in free field).
// Deterministic: the same seed gives identical histograms for any thread count (core/parallel.h).
#include <cstddef>
#include <cstdint>
#include <functional>
#include <vector>

#include "diffray/core/bands.h"
#include "diffray/receiver/direction_histogram.h"
#include "diffray/receiver/energy_histogram.h"
#include "diffray/receiver/sphere.h"
#include "diffray/room/room.h"
#include "diffray/transport/room_geometry.h"
#include "diffray/transport/room_occluders.h"

namespace diffray::transport {

/// A rectangle every ray is aimed at (validation scenes: a source far from the edge zone it lights). Rays
/// leave toward points drawn uniformly on it, weighted by 1/(4π·pdf) (pdf = r²/(A·|cos θ|) per steradian),
/// so only paths through the rectangle are sampled: exact when nothing else reaches the listeners.
/// With edge_fraction > 0, that fraction of the points is drawn near the rectangle's −x side (an edge):
/// the distance d from it log-uniform in d + edge_scale_m, where a diffracting edge sends rays widest.
/// With `mirrored`, half the rays (xi2 < ½) go to the rectangle and half to its mirror image in the plane
/// mirror_normal·p = mirror_offset (a specular ground perpendicular to the rectangle, not cutting it): rays
/// toward the image reflect off the ground and reach the rectangle (the image source's paths). The rectangle
/// and its image lie in one plane without overlapping, so a direction reaches at most one of them and its
/// pdf is half that target's. With `also`, the rays are shared equally between this rectangle and those
/// (each with its own image if mirrored; their `also` unused): rectangles that must not overlap, nor their
/// images, so that each direction reaches one of them and its pdf is that one's over their count.
struct EmissionTarget {
  core::Vec3 origin{0, 0, 0}, ex{1, 0, 0}, ey{0, 1, 0};
  double half_x_m = 1.0, half_y_m = 1.0;
  double edge_fraction = 0.0;
  double edge_scale_m = 0.01;
  bool mirrored = false;
  core::Vec3 mirror_normal{0, 0, 1};
  double mirror_offset = 0.0;
  std::vector<EmissionTarget> also;
};

/// The direction of an emitted ray from two uniforms in [0, 1) (xi1 the first): uniform over the sphere
/// (aim null), or toward a point of the aim rectangle as documented above; `scale` gets the ray's weight
/// 1/(4π·pdf per steradian), 1 for uniform emission.
core::Vec3 emissionDirection(const EmissionTarget* aim, const core::Vec3& source, double xi1, double xi2,
                             double& scale);

struct RoomTraceOptions {
  std::uint64_t rays = 100000;
  std::uint64_t seed = 1;
  std::uint64_t chunk_rays = 8192;
  double length_s = 1.0;         ///< rays are followed (and histograms kept) up to this time
  double bin_s = 0.001;          ///< histogram bin width
  int skip_order = 0;            ///< specular-only paths of order ≤ this are left to image sources; −1: none
  double roulette_level = 1e-6;  ///< Russian roulette below this fraction of the emitted energy (−60 dB)
  double speed_of_sound_m_s = 343.0;
  core::BandArray air_m_per_m = core::bandFill(0.0);  ///< energy attenuation per metre, per band
  std::function<void(std::uint64_t)> on_progress;     ///< rays done per chunk (thread-safe)
  /// Also tally the energy in flight (RoomTraceResult::in_flight): what the room as a whole still holds
  /// at each time, per band, integrated over each bin. Smooth with few rays: the pilot's decay estimate.
  bool in_flight = false;
  /// Also tally where each listener's energy comes from (RoomTraceResult::directions): every score adds its
  /// energy times the unit vector towards where it arrives from (the reverse of the ray's direction; for a
  /// next-event estimate, towards the occluder's point or its floor image).
  bool directions = false;
  /// WBSDF diffraction at the room's occluders (null: occluders are plain surfaces, openings pass rays
  /// straight). At its first occluder a ray that carries every band goes on in one of them, chosen at
  /// random (its energy times the band count), at one frequency drawn uniformly inside that band
  /// (as a band filter averages fringes), since the WBSDF sends each wavelength its own way; the energies become signed
  /// (paper section 4).
  const RoomOccluders* occluders = nullptr;
  /// WBSDF scatterings per path; later occluders are plain surfaces (openings pass rays straight, with the
  /// same mean energy, |t|² = 1). Each scattering multiplies the ray by a signed weight of magnitude ~ln of
  /// the edge kernel's range, so in a reverberant room that crosses a doorway many times the variance grows
  /// geometrically with this number; the first diffraction carries what a listener hears of the bending.
  int max_diffractions = 1;
  /// Next-event estimation at occluders that support it (RoomOccluders::expectedSphereScore): each WBSDF
  /// scattering adds to every visible listener the expected score of the scattered ray's next segment, and
  /// that segment itself is not scored. Unbiased like the plain estimator, with far less noise in shadows.
  bool next_event = true;
  /// With next-event estimation, at occluders that support it: the portal. Next-event estimation serves the
  /// first flight with the exact W (in one band picked at random, its energy times the band count); the ray
  /// goes on in every band along one direction drawn from the opening's far-field pattern instead of W(x,·)
  /// (RoomOccluders::scatterPortal: positive weights along openings, one per band). The later flights keep
  /// W's marginals (the energy through each point, the opening's radiation pattern) but not its correlation
  /// of position and direction. In a reverberant room the signed, single-band rays of the plain estimator are
  /// noise that outlives the near field (a listener's band could sum negative); the portal's rays carry no
  /// sign and every band. Listeners whose next-event estimate is not taken (NaN: the kernel swings through
  /// too many periods across the sphere) score the portal's first flight.
  bool portal = false;
  const EmissionTarget* aim = nullptr;  ///< null: rays leave uniformly over the sphere
  /// Independent batches the listener histograms keep apart (EnergyHistogram::closeChunk): ray i goes to
  /// batch ⌊i·batches/rays⌋ with its chunk (chunks have independent streams and QMC shifts), for the
  /// jackknife standard errors of the metrics (ir/uncertainty.h); 0 keeps none.
  int batches = 16;
};

struct RoomTraceResult {
  std::vector<receiver::EnergyHistogram> listeners;  ///< per room listener, J/m² per bin
  std::vector<receiver::DirectionHistogram> directions;  ///< per listener, with RoomTraceOptions::directions
  std::vector<std::uint64_t> crossings;  ///< per listener: segments that crossed its sphere (scored or not)
  receiver::EnergyHistogram in_flight;   ///< with RoomTraceOptions::in_flight: ∫ energy dt per band and bin
  std::uint64_t rays = 0;
  std::uint64_t segments = 0;       ///< intersection queries
  std::uint64_t escaped = 0;        ///< rays that left the geometry (a leak or a source outside)
  std::uint64_t roulette_killed = 0;
  std::uint64_t timed_out = 0;      ///< rays still alive at length_s
  std::uint64_t occluder_events = 0;  ///< WBSDF scatterings at occluders
  std::uint64_t evanescent = 0;       ///< of those, the rays that ended as evanescent waves
  double seconds = 0.0;
  void merge(const RoomTraceResult& o);
};

/// Traces `options.rays` rays from source `source_index` of `room` through `geometry`.
RoomTraceResult traceRoom(const room::Room& room, const RoomGeometry& geometry, int source_index,
                          const RoomTraceOptions& options);

/// Bins of a listener histogram of `length_s` in bins of `bin_s`, after checking that the histograms of
/// all `listeners` × `bands` fit kMaxHistogramCells cells (each cell is 4 doubles, and the parallel reduce
/// keeps about ten accumulators alive at once: 1e7 cells ≈ 3 GB at the peak). The batches (RoomTraceOptions::
/// batches) add one double per cell for each batch a live accumulator holds: an accumulator holds those of
/// its own chunks, so about threads × (batches + log2(chunks)) at the peak (two-rooms at 1M rays: 40 → 54 MB;
/// at the cap with 2 threads ≈ 3.7 GB more). Recording directions (RoomTraceOptions::directions) adds 3
/// doubles per cell to every accumulator: `directions` counts each cell 7/4 times then, to keep the same
/// bound on memory. Throws InputError naming
/// output.histogram_bin_s otherwise: before the cap a 600 s IR in 0.1 ms bins, which the scene file accepts,
/// ran the machine out of memory.
inline constexpr double kMaxHistogramCells = 1e7;
int histogramBins(double length_s, double bin_s, int bands, std::size_t listeners, bool directions = false);

/// The normalised power pattern of a first-order source, D(θ) = (a + (1 − a)cosθ)² / (a² + (1 − a)²/3),
/// whose mean over the sphere is 1; `cos_theta` is the cosine to the source's axis.
double directivityGain(const room::Directivity& d, double cos_theta);

}  // namespace diffray::transport
