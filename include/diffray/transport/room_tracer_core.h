#pragma once
// The room tracer's state and the steps of a path (internal to the transport module; traceRoom in
// room_tracer.h is the interface): room_tracer.cpp holds the hot loop (follow), scoring, roulette and
// traceRoom; room_occluder_events.cpp the WBSDF occluder events (band choice, next-event estimation, the
// plain scattering and the portal). One Tracer per traceRoom call, read-only while the threads trace; each
// thread passes its own accumulator (RoomTraceResult) and generator. Units: metres, seconds, J/m².
#include <embree3/rtcore.h>

#include <cstdint>
#include <vector>

#include "diffray/core/rng.h"
#include "diffray/receiver/sphere.h"
#include "diffray/transport/room_lanes.h"
#include "diffray/transport/room_materials.h"
#include "diffray/transport/room_tracer.h"

namespace diffray::transport::detail {

using core::Vec3;

struct Tracer {
  const room::Room& room;
  const RoomGeometry& geometry;
  const RoomTraceOptions& opt;
  MaterialTable materials;
  std::vector<receiver::Sphere> spheres;
  /// Two listener spheres for score's pre-test, one per lane (an unused lane: a sphere no segment nears).
  struct ListenerPair {
    Pair x, y, z;         ///< centres (m)
    Pair r_slack;         ///< radii plus a margin (m)
    Pair r2_plus_margin;  ///< r² plus a margin (m²)
  };
  std::vector<ListenerPair> listener_pairs;
  int pair_count = 0;  ///< listener_pairs.size(), as the pre-test's loop bound
  int bands = 0, bins = 0;
  double ray_energy = 0.0;  ///< emitted energy per ray per band before the directivity weight
  double max_path_m = 0.0;
  double eps_m = 0.0;
  std::vector<double> air_table;     ///< [bin][band]: e^{−m_b·s_k}, s_k the path length at bin k's centre
  std::vector<double> air_centre_m;  ///< s_k
  std::vector<int> floor_plane;      ///< per occluder: the plane of nextEventViaFloor (a door's sill, the ground under an edge), or −1
  std::vector<char> special;         ///< per triangle: an occluder's, an opening or absorbing (the cold path)

  // Scores the segment pos + t·dir, t in [0, t_end), into every listener it crosses.
  // Segments of paths the image sources cover (`skip`) are counted as crossings but not scored, nor by the
  // listeners whose score next-event estimation took (bit l of `skip_listeners`).
  // NB: the band count when known at compile time (the loops over bands unroll and vectorise), else 0.
  // `energy` times `scale` is the path's band energies (Octaves hold them relative to the emitted level).
  template <int NB, class Energy>
  void score(RoomTraceResult& acc, const Vec3& pos, const Vec3& dir, double t_end, double path_m,
             const Energy& energy, double scale, bool skip, std::uint64_t skip_listeners = 0) const;

  // score's part for listener l, whose sphere the segment may cross.
  template <int NB, class Energy>
  void scoreListener(RoomTraceResult& acc, std::size_t l, const double* o, const double* d, double t_end,
                     double path_m, const Energy& energy, double scale, bool skip,
                     std::uint64_t skip_listeners) const;

  // The nearest surface along origin + t·dir: rtcIntersect1 straight on the Embree scene (this loop's
  // hottest call), or the intersector (brute force, tests). `interior`: the hit's barycentrics are all
  // above 1e-4, far from any edge compared with float rounding.
  struct SegmentHit {
    double t = 0.0;
    int triangle = -1;
    bool interior = false;
    bool valid() const { return triangle >= 0; }
  };
  SegmentHit cast(const Vec3& o, const Vec3& d) const;
  // `rh`: a ray from makeRayHit (tnear 0), re-aimed here for each segment of a path (aimRayHit).
  SegmentHit cast(const Vec3& o, const Vec3& d, RTCIntersectContext& context, RTCRayHit& rh) const;

  // The energy the ray holds over the segment [path_m, path_m + length), spread over the time bins it
  // spans (air absorption at the segment's start: the pilot needs the decay, not a precise level).
  template <class Energy>
  void addInFlight(RoomTraceResult& acc, double path_m, double length, const Energy& energy, double scale) const;

  // The state of one path: where it is, where it goes, its band energies (a single band after a WBSDF
  // occluder split it, `band` ≥ 0 with wavelength `lambda_m`), and what decides its scoring.
  struct Path {
    Vec3 pos, dir;
    core::BandArray e;
    double path_m = 0.0;
    int order = 0;
    bool specular_chain = true;
    int band = -1;
    double lambda_m = 0.0;
    int diffractions = 0;
    double e_start = 0.0;  ///< the level Russian roulette is relative to
    std::uint64_t skip_next_score = 0;  ///< listeners (bit l) whose next-segment score next-event estimation took
    std::uint64_t skip_after_floor = 0;  ///< ... and whose score after a specular bounce off `floor_plane`
    int floor_plane = -1;
    bool has_qmc = false;  ///< qmc[] holds the first occluder's quasi-random uniforms (shift x2, band)
    double qmc[3] = {0, 0, 0};
  };

  void tracePath(RoomTraceResult& acc, core::FastRng& rng, const Vec3& start, const Vec3& dir0,
                 const core::BandArray& energy0, const double* qmc = nullptr) const;

  // The bands with energy (live[0 … n)), the one picked uniformly among them and the place of the
  // frequency inside it, in [0, 1), from one uniform (quasi-random at the path's first occluder).
  struct BandPick {
    int live[core::kMaxBands];
    int n = 0, pick = 0;
    double place = 0.0;
  };
  BandPick pickBand(core::FastRng& rng, const Path& s) const;
  // The wavelength at `place` in [0, 1) across band b.
  double wavelengthAt(int b, double place) const;

  // The bands part ways: the path goes on in one band, chosen uniformly among those with energy (its energy
  // times their count keeps every band unbiased), at one frequency drawn uniformly inside the band
  // (as a band filter averages fringes). One band rather than a split into all of them: a split multiplies the work
  // after a doorway by the band count (5× slower on two-rooms) for the same variance per unit of time.
  void chooseBand(core::FastRng& rng, Path& s) const;

  // Next-event estimation at occluder k (RoomOccluders::expectedSphereScore): every listener in view of the
  // hit point gets the expected score of the scattered ray's next segment, at its arrival time, with the
  // air absorption of the whole path. Returns the listeners it served (bit l; the first 64), whose score
  // of that segment the ray must then skip; the others score it as usual. Where the quadrature declines
  // (NaN: too many kernel periods across the sphere) a listener is left to the ray, or, with
  // `sample_when_nan` (the portal, whose ray does not follow W), served by one direction drawn from W
  // (sampledSphereScore), so that which listeners are served does not depend on the band picked.
  std::uint64_t nextEvent(RoomTraceResult& acc, core::FastRng& rng, const Path& s, int k, const Vec3& n_in,
                          std::uint64_t& floor_served, bool sample_when_nan) const;

  // One draw of the score that expectedSphereScore integrates: a direction from W at the hit point
  // (RoomOccluders::scatter, signed weight), scored by the sphere it crosses (chord over cross-section).
  double sampledSphereScore(core::FastRng& rng, const Path& s, int k, const Vec3& centre, double radius_m) const;

  // Next-event estimation through one specular bounce off occluder k's floor plane (a door's sill, the
  // ground under an edge or a barrier: floorPlaneOf in room_tracer.cpp): the listener's image below the
  // floor seen from the hit point, if that line meets the floor on a triangle of
  // its plane and the reflected leg reaches the listener, times the floor's specular reflectance
  // (1 − α)(1 − s). True when it served the listener (the ray then skips its score after such a bounce).
  bool nextEventViaFloor(RoomTraceResult& acc, core::FastRng& rng, const Path& s, int k, const Vec3& n_in,
                         std::size_t l, const double* xi, bool sample_when_nan) const;

  // The path leaves an occluder along `dir`, just off its plane on the side it goes to.
  void leaveOccluder(Path& s, const Vec3& dir, const Vec3& n_in) const;

  // At an opening that returns energy (RoomOccluders::returnsEnergy): whether the path goes through or comes
  // back, from one uniform. Band b goes through with τ_b (RoomOccluders::transmission) and comes back with
  // (1 − τ_b)·R_b (the surround's reflectance); the path goes through with probability p_t = Σ|e_b|τ_b/Σ|e_b|
  // (its energies' mean τ, so that the fates of a path that carries one band are exact) and each fate's
  // weights divide by its probability: every band's expectation is exact.
  struct OpeningFate {
    bool back = false;
    double p_through = 1.0;
    core::BandArray tau = core::bandFill(1.0);
  };
  OpeningFate openingFate(core::FastRng& rng, const Path& s, int k) const;
  // The path comes back off the wall around occluder k: its energies times (1 − τ_b)·R_b/(1 − p_t), along
  // the specular reflection off the occluder's plane, on the side it came from. Not a diffraction; next-event
  // estimation served the transmitted flight, so no listener's score is skipped.
  void comeBack(Path& s, int k, const OpeningFate& f, const Vec3& n_in) const;
  // At a WBSDF occluder event: where k returns energy, the path's fate; true when it came back (comeBack
  // done), else `through` gets 1/p_t, the factor on the transmitted weights.
  bool turnsBack(core::FastRng& rng, Path& s, int k, const Vec3& n_in, double& through) const;
  // An opening that returns energy, met once the path's WBSDF scatterings are spent: through it along the
  // same direction (energies times τ_b/p_t) or back off its wall (comeBack).
  void passOpening(core::FastRng& rng, Path& s, int k, const Vec3& n_in) const;

  // A WBSDF occluder event for a single-band path at the hit point (paper eq. 8–10); false when it ends.
  bool scatterAtOccluder(RoomTraceResult& acc, core::FastRng& rng, Path& s, int k, const Vec3& n_in) const;

  // The portal at occluder k (RoomTraceOptions::portal) for a path that carries every band: next-event
  // estimation in one band picked uniformly (its energy times the live band count, so each band is served
  // in expectation), at one frequency in it; the path goes on in every band along one direction from
  // RoomOccluders::scatterPortal, each band at a frequency at the same place in its band. False when it ends.
  bool portalAtOccluder(RoomTraceResult& acc, core::FastRng& rng, Path& s, int k, const Vec3& n_in) const;

  // Follows a path until it ends. The hot state lives in locals (not in the Path, which the occluder code
  // takes by reference and would make every store in the loop a possible alias): 5 % of the room bench.
  template <int NB>
  void follow(RoomTraceResult& acc, core::FastRng& rng, Path& s) const;

  // Russian roulette relative to the emitted energy (unbiased: survivors are divided by their survival
  // probability); false when the path ends. The level is the largest |band energy| (WBSDF weights are
  // signed) and leaves air absorption out (it is applied at scoring): an upper bound of the attenuated
  // level, so rays live a little longer at high frequencies, and no exp per bounce. `threshold`: the
  // roulette level times the emitted level; `threshold4`: the same as floats rounded up (octaves only).
  template <int NB>
  bool roulette(RoomTraceResult& acc, core::FastRng& rng, typename EnergyOf<NB>::type& e, double threshold,
                Quad threshold4 = Quad{}) const;

  // Multiplies the band energies by material m's weights for one event (w8: the same as Octaves).
  template <int NB>
  void weigh(typename EnergyOf<NB>::type& e, const std::vector<core::BandArray>& w, const std::vector<Octaves>& w8,
             int m) const;
};

}  // namespace diffray::transport::detail
