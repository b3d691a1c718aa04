#pragma once
// UTD sound paths between a source and a listener in a room (Kouyoumjian & Pathak 1974): the geometric part (direct
// sound, first-order specular reflections) and first- and second-order edge diffraction, each with its
// exact length (delay = length / c) and its complex pressure at any frequency for a point source of unit
// amplitude, p = e^{−ikR}/R in free field (time factor e^{iωt}).
//
// Diffraction point (apex): Fermat's principle on each finite edge (the shortest path through points of the
// edges, the Keller cone); a path whose apex falls outside an edge segment is not a path. Every leg is
// checked with the room's intersector (openings let sound through), starting and ending a small offset
// off edges and faces into the air: offsetAt(p), absolute and set by the point's own float rounding (128
// float ulps of |p|, at least 10 µm), so that nothing depends on how large the scene is. Pressure (Kouyoumjian–Pathak, coefficient.h):
//   first order   p = (e^{−iks′}/s′) · D(L) · √(s′/(s(s′ + s))) · e^{−iks},  L = s′s sin²β0/(s′ + s);
//   second order  p = (e^{−iks′}/s′) · D1(L1) · √(s′/(s1(s′ + s1))) · D2(L2) · √(ρ/(s2(ρ + s2))) · e^{−ik(s1+s2)},
//                 ρ = s′ + s1, L1 = s′s1 sin²β1/(s′ + s1), L2 = ρ s2 sin²β2/(ρ + s2):
// the wave leaving edge 1 is treated at edge 2 as one from a point at the unfolded distance ρ, which is its
// exact caustic distance along the edges when they are parallel (a thick wall, a doorway reveal; the form
// of e.g. Tsingos et al., SIGGRAPH 2001, §3). An incident ray that grazes a face of the wedge (φ′ = 0 or
// nπ, as between the two edges of a reveal) takes D/2 (Kouyoumjian & Pathak 1974: incident and reflected
// waves merge there). Reflections: R·e^{−ikL}/L over the unfolded length L; a source or listener within the
// offset of a face's plane is on it (its image coincides with it: a rigid face doubles the field), the
// offset then only lifting it for the visibility test.
//
// Face reflection coefficients: UtdOptions::face_reflection for every face (+1 rigid), or with
// material_reflection √(1 − α) of the face's material in the band that holds the frequency. Air absorption
// and source directivity are not applied (the caller's). Units: metres, Hz, m/s, seconds.
// Thread-safety: a UtdModel is immutable after construction; every method is const and thread-safe. It
// keeps references to the room and the geometry, which must outlive it.
#include <complex>
#include <vector>

#include "diffray/core/bands.h"
#include "diffray/room/room.h"
#include "diffray/transport/room_geometry.h"
#include "diffray/utd/edges.h"

namespace diffray::utd {

struct UtdOptions {
  int max_order = 2;                 ///< highest diffraction order (0, 1 or 2)
  bool reflections = true;           ///< first-order specular reflections in the geometric part
  double face_reflection = 1.0;      ///< R of every face and wedge face: +1 rigid, −1 soft
  bool material_reflection = false;  ///< use √(1 − α(band)) of each face's material instead
  EdgeOptions edges;
};

enum class PathKind { Direct, Reflection, Diffraction };

/// Geometry of one diffraction on a path, in the edge's frame (edges.h).
struct Diffraction {
  int edge = -1;
  double phi_in = 0.0;   ///< φ′: direction the incident ray comes from
  double phi_out = 0.0;  ///< φ: direction the diffracted ray leaves towards
  double beta0 = 0.0;    ///< angle between the rays and the edge (Keller's cone)
  double l_m = 0.0;      ///< UTD distance parameter L
  bool grazing = false;  ///< incidence along a face: D is halved
};

struct Path {
  PathKind kind = PathKind::Direct;
  int order = 0;                         ///< diffractions (Diffraction) or reflections (Reflection)
  std::vector<int> edges;                ///< indices into UtdModel::edges(), in path order
  std::vector<Diffraction> diffractions; ///< one per edge
  int triangle = -1;                     ///< the reflecting triangle (Reflection)
  std::vector<core::Vec3> points;        ///< source, apexes or reflection point, listener
  double length_m = 0.0;
  /// Geometric paths: ½ when the listener lies on a shadow boundary of a first-order diffraction (within
  /// 1e-9 rad), where the transition function takes the mean of its two sides: the incident boundary for
  /// the direct path, a face's reflection boundary for the reflection off that face; 1 otherwise.
  double gain = 1.0;
  double delay(double c_m_s) const { return length_m / c_m_s; }
};

/// Per-band energy of one path: mean of |p|² over a uniform frequency grid inside each band, in the room
/// tracer's units (a 1 W omni source has fluence 1/r² in free field, i.e. |p|² of e^{−ikR}/R), to be added
/// to the band × time histogram at delay_s.
struct PathEnergy {
  int path = -1;  ///< index into the path list
  double delay_s = 0.0;
  core::BandArray energy = core::bandFill(0.0);
};

class UtdModel {
 public:
  UtdModel(const room::Room& room, const transport::RoomGeometry& geometry, UtdOptions options = {});

  const std::vector<Edge>& edges() const { return edges_; }
  const UtdOptions& options() const { return options_; }

  /// Every path from `source` to `listener`: direct (if visible), reflections (if enabled), then
  /// diffractions of order 1 and 2 (up to max_order).
  std::vector<Path> paths(const core::Vec3& source, const core::Vec3& listener) const;
  /// Complex pressure of one path at `freq_hz` (unit-amplitude point source).
  std::complex<double> pressure(const Path& path, double freq_hz, double c_m_s) const;
  /// Sum of pressure() over the paths.
  std::complex<double> total(const std::vector<Path>& paths, double freq_hz, double c_m_s) const;
  /// Per-band energies of the diffraction paths (all paths with diffraction_only = false), `points`
  /// frequencies per band at the midpoints of equal slices of [lower, upper] of room.bands.
  std::vector<PathEnergy> bandEnergies(const std::vector<Path>& paths, double c_m_s, int points = 16,
                                       bool diffraction_only = true) const;

 private:
  bool visible(const core::Vec3& from, const core::Vec3& to) const;
  double faceReflection(int material, double freq_hz) const;
  void addReflections(const core::Vec3& s, const core::Vec3& r, std::vector<Path>& out) const;
  void addFirstOrder(const core::Vec3& s, const core::Vec3& r, std::vector<Path>& out) const;
  void addSecondOrder(const core::Vec3& s, const core::Vec3& r, std::vector<Path>& out) const;
  /// Fills a Diffraction for edge e with incidence from `from`, leaving towards `to`; false when either
  /// lies outside the air sector or along the edge.
  bool diffraction(int e, const core::Vec3& apex, const core::Vec3& from, const core::Vec3& to, double l_m,
                   Diffraction& d) const;
  /// Gives the reflection off face `face` (0, or 1 for face n) of edge e gain ½, adding it when the
  /// triangle test missed its reflection point on the edge (listener on that face's reflection boundary).
  void halveReflection(int e, int face, const core::Vec3& s, const core::Vec3& r, std::vector<Path>& out) const;
  core::Vec3 offEdge(int e, const core::Vec3& apex) const;
  /// Whether the reflection point p (on `reflecting`) lies on another surface that s and r stand on opposite
  /// sides of, as where a barrier stands on the ground: the specular path then passes through that surface
  /// at its foot (a visibility test from a point lifted off p cannot see it).
  bool crossesSurfaceAt(const transport::MirrorPlane& reflecting, const core::Vec3& p, const core::Vec3& s,
                        const core::Vec3& r) const;
  /// The offset (m) of a point at p off an edge or face: max(10 µm, 128·FLT_EPSILON·max|p_i|).
  static double offsetAt(const core::Vec3& p);

  const room::Room& room_;
  const transport::RoomGeometry& geometry_;
  UtdOptions options_;
  std::vector<Edge> edges_;
  std::vector<char> opening_;  ///< per material
  core::Vec3 centre_{0, 0, 0};  ///< of the mesh's bounding box
};

}  // namespace diffray::utd
