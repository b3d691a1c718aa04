// UtdModel (utd/paths.h): construction, visibility, the list of paths with the listener on a shadow or
// reflection boundary, and the pressure of a path. The geometric paths are found in reflection_paths.cpp,
// the diffracted ones in diffraction_paths.cpp.
#include "diffray/utd/paths.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <utility>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/utd/coefficient.h"

namespace diffray::utd {

using core::Vec3;
using cd = std::complex<double>;

UtdModel::UtdModel(const room::Room& room, const transport::RoomGeometry& geometry, UtdOptions options)
    : room_(room), geometry_(geometry), options_(std::move(options)) {
  if (options_.max_order < 0 || options_.max_order > 2)
    throw core::InputError("utd max_order", "must be 0, 1 or 2");
  if (options_.second_order_reflections < 0 || options_.second_order_reflections > 3)
    throw core::InputError("utd second_order_reflections", "must be 0, 1, 2 or 3");
  core::requireFinite("utd face_reflection", options_.face_reflection);
  edges_ = extractEdges(room, geometry, options_.edges);
  for (int m = 0; m < static_cast<int>(room.materials.size()); ++m) opening_.push_back(room.isOpening(m) ? 1 : 0);
  findEdgeRanges();
  if (!room.mesh.vertices.empty()) {
    Vec3 lo = room.mesh.vertices[0], hi = lo;
    for (const Vec3& v : room.mesh.vertices) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
    centre_ = 0.5 * (lo + hi);
  }
}

bool UtdModel::visible(const Vec3& a, const Vec3& b) const {
  // Embree works in float: trace from the end nearer the geometry, so that a far source's rounding
  // (1e-7 of its distance) does not move the ray near the edges and faces it must pass.
  const bool swap = (a - centre_).squaredNorm() > (b - centre_).squaredNorm();
  const Vec3& from = swap ? b : a;
  const Vec3& to = swap ? a : b;
  const Vec3 d = to - from;
  const double len = d.norm();
  if (!(len > 0.0)) return true;
  const Vec3 dir = d / len;
  double tnear = 0.0;
  for (int guard = 0; guard < 64; ++guard) {
    const geometry::Hit hit = geometry_.intersector().intersect(geometry::Ray{from, dir, tnear, len});
    if (!hit.valid()) return true;
    if (!opening_[hit.object]) return false;
    tnear = hit.t + offsetAt(from + hit.t * dir);  // an opening lets sound through: look past it
  }
  return false;
}

double UtdModel::faceReflection(int material, double freq_hz) const {
  if (!options_.material_reflection || material < 0) return options_.face_reflection;
  const core::Bands& bands = room_.bands;
  int b = 0;
  while (b + 1 < bands.size() && freq_hz > bands.upperHz(b)) ++b;
  return std::sqrt(std::max(0.0, 1.0 - room_.materials[material].absorption[b]));
}

double UtdModel::offsetAt(const Vec3& p) {
  // Embree holds the scene in float: a coordinate of size |p| is known to FLT_EPSILON·|p|; 128 of those
  // (1.5e-4 m at 10 m, 1.5 cm at 1 km) lift a point clear of that rounding, and 10 µm near the origin.
  return std::max(1e-5, 128.0 * FLT_EPSILON * p.cwiseAbs().maxCoeff());
}

Vec3 UtdModel::offEdge(int e, const Vec3& apex) const { return apex + offsetAt(apex) * edges_[e].bisector(); }

bool UtdModel::apexWithinEdge(const Diffraction& d) const {
  const double length = edges_[d.edge].length_m, tol = 1e-9 * length;
  return d.arc_m >= -tol && d.arc_m <= length + tol;
}

double UtdModel::phiOf(int e, const Vec3& p) const {
  const double phi = edges_[e].phi(p);
  return phi > core::kTwoPi - 1e-9 ? 0.0 : phi;  // a point exactly on face 0 may come out as 2π − tiny
}

bool UtdModel::diffraction(int e, const Vec3& apex, const Vec3& from, double phi_in, double phi_out, double l_m,
                           Diffraction& d) const {
  const Edge& edge = edges_[e];
  const double wedge = edge.wedge_n * core::kPi, tol = 1e-9;
  d.edge = e;
  d.phi_in = phi_in;
  d.phi_out = phi_out;
  if (d.phi_in > wedge + tol || d.phi_out > wedge + tol) return false;
  const Vec3 in = (apex - from).normalized();
  d.beta0 = std::acos(std::clamp(in.dot(edge.tangent), -1.0, 1.0));
  if (!(std::sin(d.beta0) > 1e-6)) return false;
  d.l_m = l_m * std::sin(d.beta0) * std::sin(d.beta0);
  d.grazing = std::min(d.phi_in, wedge - d.phi_in) < 1e-6;
  return true;
}

std::vector<Path> UtdModel::paths(const Vec3& source, const Vec3& listener) const {
  std::vector<Path> out;
  if (visible(source, listener)) {
    Path direct;
    direct.points = {source, listener};
    direct.length_m = (listener - source).norm();
    out.push_back(std::move(direct));
  }
  if (options_.reflections) addReflections(source, listener, out);
  if (options_.max_order >= 1) addDiffractions(1, source, listener, out);
  // A listener on a shadow boundary of an edge: the incident one (φ = φ′ ± π) or the reflection one of face 0
  // (φ + φ′ = π) or face n (φ + φ′ = (2n − 1)π). Embree's visibility of the ray grazing the edge, and the
  // triangle test of a reflection point on the edge, are decided by rounding, while the diffracted term
  // takes the mean of its two sides (coefficient.h): the geometric field there is half of the full one,
  // whatever the tests said (Kouyoumjian & Pathak 1974). For the diffraction of the source's or listener's
  // image in a plane, the incident boundary is the one of the reflection off that plane.
  const double tol = kBoundaryTolRad;
  bool on_boundary = false;
  std::vector<std::pair<int, int>> reflection_boundaries;  // (edge, face: 0 or 1 for face n)
  std::vector<std::pair<int, int>> mirrored_boundaries;    // (plane, triangle)
  for (const Path& p : out) {
    if (p.kind != PathKind::Diffraction || p.order != 1 || p.bounces.size() > 1) continue;
    const Diffraction& d = p.diffractions[0];
    if (!apexWithinEdge(d)) continue;  // a corner's wave: the edge's boundaries do not reach past its end
    const bool incident = std::abs(std::abs(d.phi_out - d.phi_in) - core::kPi) < tol;
    if (!p.bounces.empty()) {
      const int t = p.bounces[0].triangle;
      if (incident) mirrored_boundaries.push_back({geometry_.triangle(t).plane, t});
      continue;
    }
    on_boundary = on_boundary || incident;
    const double sum = d.phi_out + d.phi_in, n = edges_[d.edge].wedge_n;
    if (std::abs(sum - core::kPi) < tol) reflection_boundaries.push_back({d.edge, 0});
    if (std::abs(sum - (2.0 * n - 1.0) * core::kPi) < tol) reflection_boundaries.push_back({d.edge, 1});
  }
  if (on_boundary) {
    if (out.empty() || out[0].kind != PathKind::Direct) {
      Path direct;
      direct.points = {source, listener};
      direct.length_m = (listener - source).norm();
      out.insert(out.begin(), std::move(direct));
    }
    out[0].gain = 0.5;
  }
  if (options_.reflections) {
    for (const auto& [e, face] : reflection_boundaries) halveReflection(e, face, source, listener, out);
    for (const auto& [plane, tri] : mirrored_boundaries) halvePlaneReflection(plane, tri, source, listener, out);
  }
  if (options_.max_order >= 2) addDiffractions(2, source, listener, out);
  return out;
}

std::complex<double> UtdModel::pressure(const Path& path, double freq_hz, double c_m_s) const {
  core::requirePositive("utd frequency", freq_hz);
  core::requirePositive("utd speed of sound", c_m_s);
  const double k = core::kTwoPi * freq_hz / c_m_s;
  const cd phase = std::exp(cd(0.0, -k * path.length_m));
  if (path.kind == PathKind::Direct) return path.gain * phase / path.length_m;
  if (path.kind == PathKind::Reflection)
    return path.gain * faceReflection(room_.mesh.object_of_triangle[path.triangle], freq_hz) * phase / path.length_m;
  // Diffraction: (1/s′)·Π D_i·A_i·Π R_j·e^{−ik·length}, A_i = √(ρ_i/(s_i(ρ_i + s_i))), ρ_i the unfolded
  // distance from the source to apex i and s_i the unfolded leg after it (to the next apex or the
  // listener, through any reflection points), R_j the reflecting faces'.
  const std::vector<Vec3>& pts = path.points;
  const auto unfolded = [&](int from, int to) {
    double length = 0.0;
    for (int j = from; j < to; ++j) length += (pts[j + 1] - pts[j]).norm();
    return length;
  };
  double rho = unfolded(0, path.diffractions[0].point);
  cd p = phase / rho;
  for (std::size_t i = 0; i < path.diffractions.size(); ++i) {
    const Diffraction& d = path.diffractions[i];
    const Edge& e = edges_[d.edge];
    const int next = i + 1 < path.diffractions.size() ? path.diffractions[i + 1].point : static_cast<int>(pts.size()) - 1;
    const double s = unfolded(d.point, next);
    const FaceReflection r{faceReflection(e.material0, freq_hz), faceReflection(e.materialn, freq_hz)};
    cd dc = wedgeCoefficient(e.wedge_n, k, d.l_m, d.phi_out, d.phi_in, d.beta0, r, truncation(d, k), apexWithinEdge(d));
    if (d.grazing) dc *= 0.5;
    p *= dc * std::sqrt(rho / (s * (rho + s)));
    rho += s;
  }
  for (const Bounce& b : path.bounces) p *= faceReflection(room_.mesh.object_of_triangle[b.triangle], freq_hz);
  return p;
}

std::complex<double> UtdModel::total(const std::vector<Path>& paths, double freq_hz, double c_m_s) const {
  cd sum = 0.0;
  for (const Path& p : paths) sum += pressure(p, freq_hz, c_m_s);
  return sum;
}

std::vector<PathEnergy> UtdModel::bandEnergies(const std::vector<Path>& paths, double c_m_s, int points,
                                               bool diffraction_only) const {
  if (points < 1) throw core::InputError("utd band points", "must be at least 1");
  const core::Bands& bands = room_.bands;
  std::vector<PathEnergy> out;
  for (std::size_t i = 0; i < paths.size(); ++i) {
    if (diffraction_only && paths[i].kind != PathKind::Diffraction) continue;
    PathEnergy pe;
    pe.path = static_cast<int>(i);
    pe.delay_s = paths[i].delay(c_m_s);
    for (int b = 0; b < bands.size(); ++b) {
      const double lo = bands.lowerHz(b), width = bands.upperHz(b) - lo;
      double sum = 0.0;
      for (int j = 0; j < points; ++j) sum += std::norm(pressure(paths[i], lo + (j + 0.5) * width / points, c_m_s));
      pe.energy[b] = sum / points;
    }
    out.push_back(pe);
  }
  return out;
}

}  // namespace diffray::utd
