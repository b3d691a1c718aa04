#pragma once
// UTD sound paths between a source and a listener in a room (Kouyoumjian & Pathak 1974): the geometric part (direct
// sound, first-order specular reflections) and first- and second-order edge diffraction on every extracted
// edge, each diffraction optionally with a first-order specular reflection before it, after it and (second
// order) between the edges; each path with its exact length (delay = length / c) and its complex pressure at
// any frequency for a point source of unit amplitude, p = e^{−ikR}/R in free field (time factor e^{iωt}).
//
// Diffraction point (apex): Fermat's principle on each finite edge (the shortest path through points of the
// edges, the Keller cone); a path whose apex falls outside an edge segment is not a path (but for the wave of
// a first-order edge's corner, "Finite edges" below). Every leg is
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
// waves merge there). Between two edges of one thin plate the path runs along either face of it: two paths,
// each grazing (the two faces of the BTM plate's second-order term, reference/btm_plate.h). Reflections:
// R·e^{−ikL}/L over the unfolded length L; a source or listener within the offset of a face's plane is on
// it (its image coincides with it: a rigid face doubles the field), the offset then only lifting it for the
// visibility test.
//
// Diffraction with reflections (UtdOptions::reflected_diffraction): the image source in a face's plane
// before an edge, the image listener after it, and at second order the second edge mirrored in a plane
// between the edges, unfold the path into a plain one, whose apexes, angles φ′, φ, β0 and distances s′, s are
// the unfolded ones (the image principle: a ray reflected off a plane continues straight from the image);
// the pressure takes each face's R as well. Each reflection point must lie on a triangle of its plane, the
// points before and after it on the plane's same side, and every leg must be clear. A face that holds the
// edge is not a reflection for it (its reflection is part of D), and neither is a reflection point on another
// diffracting edge (other than the apex itself): a path that grazes one face of a box and "reflects" off the
// next face at their common edge is that edge's diffraction, and counting it again would triple each
// edge-to-edge path around a box. A crease that does not diffract (a barrier's foot on the ground) reflects:
// the path runs on through the image of what stands on it. Where the reflection point falls on the apex
// (an edge standing on the reflecting plane, the apex at its foot), the path through the edge and its
// mirror image is one path: it is kept once, as the reflection before the apex. A second-order path takes
// at most UtdOptions::second_order_reflections of its three. A listener on the incident shadow boundary of
// the source's (or its own) image diffracted at an edge gets the reflection off that plane at half strength,
// as the direct sound on a plain edge's boundary.
//
// Finite edges (UtdOptions::finite_edges): UTD is the stationary-phase value of the BTM edge-source integral
// over an infinite edge (Svensson, Fred & Vanderkooy 1999); over a finite one the integral of the phase
// e^{−ik(m + l)} ≈ e^{−ik(s′ + s)}·e^{−iτ²} runs between the ends only, τ = (z − z_a)·√(kP″/2), P″ = sin²β0·
// (1/s′ + 1/s) the curvature of the path length along the edge at the apex z_a (the unfolded distances), so
// a first-order diffraction takes T = ∫_{τ0}^{τ1} e^{−iτ²}dτ / ∫_{−∞}^{∞} e^{−iτ²}dτ (a stationary point
// near an end point, Felsen & Marcuvitz, Radiation and Scattering of Waves, 1973, §4.2). Where the apex lies
// beyond a free end, within three units of τ at the lowest band's lower frequency, the tail is kept: the
// wave of the edge's corner. Each term of D takes (apex on the edge ? 1 − |F(X)| : 0) + |F(X)|·T
// (coefficient.h), an interpolation between a term on its shadow or reflection boundary, whose integrand is
// concentrated at the apex (in full on the edge, so the total field stays continuous there; nothing beyond
// its end), and one far from it, whose amplitude is smooth over the Fresnel zone (T). An end on a plane
// perpendicular to the edge (a foot standing on a face) is no end: the edge continues as its mirror image;
// an edge between two such planes is infinite. Second-order diffractions are not truncated.
//
// Face reflection coefficients: UtdOptions::face_reflection for every face (+1 rigid), or with
// material_reflection √(1 − α) of the face's material in the band that holds the frequency. Air absorption
// and source directivity are not applied (the caller's). Units: metres, Hz, m/s, seconds.
// Thread-safety: a UtdModel is immutable after construction; every method is const and thread-safe. It
// keeps references to the room and the geometry, which must outlive it.
#include <complex>
#include <utility>
#include <vector>

#include "diffray/core/bands.h"
#include "diffray/room/room.h"
#include "diffray/transport/room_geometry.h"
#include "diffray/utd/edges.h"

namespace diffray::utd {

struct UtdOptions {
  int max_order = 2;                 ///< highest diffraction order (0, 1 or 2)
  bool reflections = true;           ///< first-order specular reflections in the geometric part
  /// Diffraction paths with first-order specular reflections around the edges: before and after a
  /// first-order diffraction, before, between and after a second-order one.
  bool reflected_diffraction = true;
  /// The most reflections on one second-order diffraction path (0 to 3). Each multiplies the paths to try by
  /// the number of planes: 1 keeps a furnished room fast, 3 is complete for first-order reflections.
  int second_order_reflections = 1;
  /// First-order diffraction on each edge's finite length (the header's T) and off its free ends; false:
  /// every edge as if it went on without end, and only apexes on it.
  bool finite_edges = true;
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
  int point = -1;        ///< index of the apex in Path::points
  double arc_m = 0.0;      ///< the apex's arc length on the edge's line (beyond its ends for a corner's wave)
  double curvature = 0.0;  ///< P″ (1/m) for the finite-edge factor; 0: not truncated (second order)
};

/// A specular reflection on a diffraction path.
struct Bounce {
  int triangle = -1;  ///< the reflecting triangle (its material's R)
  int point = -1;     ///< index of the reflection point in Path::points
};

struct Path {
  PathKind kind = PathKind::Direct;
  int order = 0;                         ///< diffractions (Diffraction) or reflections (Reflection)
  std::vector<int> edges;                ///< indices into UtdModel::edges(), in path order
  std::vector<Diffraction> diffractions; ///< one per edge
  int triangle = -1;                     ///< the reflecting triangle (Reflection)
  std::vector<Bounce> bounces;           ///< specular reflections on a Diffraction path, in path order
  std::vector<core::Vec3> points;        ///< source, the apexes and reflection points in path order, listener
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
  /// One candidate diffraction path: its edges and the reflecting plane (index into geometry.planes(), or
  /// −1 for none) before the first edge, between the edges (second order) and after the last one.
  struct Candidate {
    int order = 1;
    int edge[2] = {-1, -1};
    int mirror[3] = {-1, -1, -1};  ///< before, (between,) after: mirror[order] is the one after
  };

  bool visible(const core::Vec3& from, const core::Vec3& to) const;
  double faceReflection(int material, double freq_hz) const;
  // Geometric part (reflection_paths.cpp).
  void addReflections(const core::Vec3& s, const core::Vec3& r, std::vector<Path>& out) const;
  /// Gives the reflection off face `face` (0, or 1 for face n) of edge e gain ½, adding it when the
  /// triangle test missed its reflection point on the edge (listener on that face's reflection boundary).
  void halveReflection(int e, int face, const core::Vec3& s, const core::Vec3& r, std::vector<Path>& out) const;
  /// Gives the reflection off plane `plane` gain ½, adding it (off `triangle`) when the visibility test
  /// missed it: the listener is on the incident shadow boundary of a diffraction of the source's image in it.
  void halvePlaneReflection(int plane, int triangle, const core::Vec3& s, const core::Vec3& r,
                            std::vector<Path>& out) const;
  /// The non-opening triangle of plane `plane` that holds p (in its plane), or −1.
  int triangleAt(int plane, const core::Vec3& p) const;
  /// Whether the reflection point p (on `reflecting`) lies on another surface that s and r stand on opposite
  /// sides of, as where a barrier stands on the ground: the specular path then passes through that surface
  /// at its foot (a visibility test from a point lifted off p cannot see it).
  bool crossesSurfaceAt(const transport::MirrorPlane& reflecting, const core::Vec3& p, const core::Vec3& s,
                        const core::Vec3& r) const;
  /// Whether p lies on one of the extracted edges (within offsetAt(p)): a reflection there is part of that
  /// edge's diffraction, not a specular path of its own.
  bool onEdge(const core::Vec3& p) const;
  // Diffraction (diffraction_paths.cpp).
  /// Every diffraction path of `order` (1 or 2), with reflections around the edges if enabled.
  void addDiffractions(int order, const core::Vec3& s, const core::Vec3& r, std::vector<Path>& out) const;
  /// Adds the paths of candidate c (none, one, or one per face of a thin plate the leg between the edges
  /// runs along) whose apexes lie on the edges, reflection points on their faces and legs in the clear.
  void tryCandidate(const Candidate& c, const core::Vec3& s, const core::Vec3& r, std::vector<Path>& out) const;
  /// Fills a Diffraction for edge e at `apex` with incidence from direction φ′ = phi_in (the ray from
  /// `from`) leaving towards φ = phi_out; false when either lies outside the air sector or the ray runs along
  /// the edge.
  bool diffraction(int e, const core::Vec3& apex, const core::Vec3& from, double phi_in, double phi_out, double l_m,
                   Diffraction& d) const;
  /// Whether d's apex lies on its edge (not beyond an end).
  bool apexWithinEdge(const Diffraction& d) const;
  /// φ of point p about edge e in [0, 2π), a point on face 0 read as 0 (not 2π − rounding).
  double phiOf(int e, const core::Vec3& p) const;
  // Finite edges (finite_edges.cpp).
  /// Per edge, the arc range its finite-edge factor integrates over: its ends, or beyond an end standing
  /// on a plane perpendicular to it (its mirror image continues it), ±infinity for such planes at both ends.
  void findEdgeRanges();
  /// The finite-edge factor T of a first-order diffraction at wavenumber k (1 for second order or
  /// finite_edges off).
  std::complex<double> truncation(const Diffraction& d, double k) const;
  /// Whether an apex at arc length `arc` off edge e is kept as its corner's wave: beyond a free end (not a
  /// foot), its tail within three units of τ at the lowest band's lower frequency, with P″ = curvature.
  bool keepsCorner(int e, double arc, double curvature) const;
  /// The edge's air point for visibility tests: the apex moved the offset along the bisector.
  core::Vec3 offEdge(int e, const core::Vec3& apex) const;
  /// The offset (m) of a point at p off an edge or face: max(10 µm, 128·FLT_EPSILON·max|p_i|).
  static double offsetAt(const core::Vec3& p);

  const room::Room& room_;
  const transport::RoomGeometry& geometry_;
  UtdOptions options_;
  std::vector<Edge> edges_;
  std::vector<std::pair<double, double>> range_;  ///< per edge: findEdgeRanges
  std::vector<char> opening_;  ///< per material
  core::Vec3 centre_{0, 0, 0};  ///< of the mesh's bounding box
};

}  // namespace diffray::utd
