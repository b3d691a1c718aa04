#include "diffray/utd/paths.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <utility>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/utd/apex.h"
#include "diffray/utd/coefficient.h"

namespace diffray::utd {

using core::Vec3;
using cd = std::complex<double>;

namespace {

// A first-order specular path s → p → r off triangle `tri`, unfolded length `length_m`, amplitude `gain`.
Path reflectionPath(int tri, const Vec3& s, const Vec3& p, const Vec3& r, double length_m, double gain) {
  Path path;
  path.kind = PathKind::Reflection;
  path.order = 1;
  path.triangle = tri;
  path.points = {s, p, r};
  path.length_m = length_m;
  path.gain = gain;
  return path;
}

// A point-in-triangle test in the triangle's plane (barycentric, tolerance relative to its size).
bool insideTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 n = (b - a).cross(c - a);
  const double n2 = n.squaredNorm();
  if (!(n2 > 0.0)) return false;
  const double u = (c - b).cross(p - b).dot(n) / n2, v = (a - c).cross(p - c).dot(n) / n2;
  const double w = 1.0 - u - v, tol = 1e-9;
  return u >= -tol && v >= -tol && w >= -tol;
}

}  // namespace

UtdModel::UtdModel(const room::Room& room, const transport::RoomGeometry& geometry, UtdOptions options)
    : room_(room), geometry_(geometry), options_(std::move(options)) {
  if (options_.max_order < 0 || options_.max_order > 2)
    throw core::InputError("utd max_order", "must be 0, 1 or 2");
  core::requireFinite("utd face_reflection", options_.face_reflection);
  edges_ = extractEdges(room, geometry, options_.edges);
  for (int m = 0; m < static_cast<int>(room.materials.size()); ++m) opening_.push_back(room.isOpening(m) ? 1 : 0);
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

bool UtdModel::crossesSurfaceAt(const transport::MirrorPlane& reflecting, const Vec3& p, const Vec3& s,
                                const Vec3& r) const {
  const double tol = offsetAt(p);
  for (const auto& other : geometry_.planes()) {
    if (&other == &reflecting) continue;
    const double dp = other.normal.dot(p) - other.offset;
    const double ds = other.normal.dot(s) - other.offset, dr = other.normal.dot(r) - other.offset;
    if (std::abs(dp) > tol || !(ds * dr < 0.0) || std::abs(ds) <= tol || std::abs(dr) <= tol) continue;
    for (int t : other.triangles) {
      if (opening_[room_.mesh.object_of_triangle[t]]) continue;
      const auto& v = room_.mesh.triangles[t];
      if (insideTriangle(p, room_.mesh.vertices[v[0]], room_.mesh.vertices[v[1]], room_.mesh.vertices[v[2]])) return true;
    }
  }
  return false;
}

double UtdModel::offsetAt(const Vec3& p) {
  // Embree holds the scene in float: a coordinate of size |p| is known to FLT_EPSILON·|p|; 128 of those
  // (1.5e-4 m at 10 m, 1.5 cm at 1 km) lift a point clear of that rounding, and 10 µm near the origin.
  return std::max(1e-5, 128.0 * FLT_EPSILON * p.cwiseAbs().maxCoeff());
}

Vec3 UtdModel::offEdge(int e, const Vec3& apex) const { return apex + offsetAt(apex) * edges_[e].bisector(); }

bool UtdModel::diffraction(int e, const Vec3& apex, const Vec3& from, const Vec3& to, double l_m,
                           Diffraction& d) const {
  const Edge& edge = edges_[e];
  const double wedge = edge.wedge_n * core::kPi, tol = 1e-9;
  d.edge = e;
  d.phi_in = edge.phi(from);
  d.phi_out = edge.phi(to);
  // Points exactly on a face may come out as 2π − tiny instead of 0.
  if (d.phi_in > core::kTwoPi - tol) d.phi_in = 0.0;
  if (d.phi_out > core::kTwoPi - tol) d.phi_out = 0.0;
  if (d.phi_in > wedge + tol || d.phi_out > wedge + tol) return false;
  const Vec3 in = (apex - from).normalized();
  d.beta0 = std::acos(std::clamp(in.dot(edge.tangent), -1.0, 1.0));
  if (!(std::sin(d.beta0) > 1e-6)) return false;
  d.l_m = l_m * std::sin(d.beta0) * std::sin(d.beta0);
  d.grazing = std::min(d.phi_in, wedge - d.phi_in) < 1e-6;
  return true;
}

void UtdModel::addReflections(const Vec3& s, const Vec3& r, std::vector<Path>& out) const {
  const auto& planes = geometry_.planes();
  for (const auto& pl : planes) {
    double ds = pl.normal.dot(s) - pl.offset, dr = pl.normal.dot(r) - pl.offset;
    // A point within the offset of the plane is on it: its image coincides with it (on a rigid plane the
    // field doubles there, the limit of the two paths as the height goes to 0). Only points farther than
    // the offset on opposite sides have no reflection.
    const bool s_on = std::abs(ds) < offsetAt(s), r_on = std::abs(dr) < offsetAt(r);
    if (!s_on && !r_on && !(ds * dr > 0.0)) continue;
    const double side = std::abs(ds) >= std::abs(dr) ? (ds >= 0.0 ? 1.0 : -1.0) : (dr >= 0.0 ? 1.0 : -1.0);
    if (!s_on && side * ds < 0.0) continue;
    if (!r_on && side * dr < 0.0) continue;
    ds = side * std::max(side * ds, 0.0);  // a point a little behind the plane is taken as on it
    dr = side * std::max(side * dr, 0.0);
    const Vec3 s_c = s - (pl.normal.dot(s) - pl.offset - ds) * pl.normal;
    const Vec3 r_c = r - (pl.normal.dot(r) - pl.offset - dr) * pl.normal;
    const Vec3 image = s_c - 2.0 * ds * pl.normal;
    const Vec3 p = ds + dr != 0.0 ? Vec3(image + (r_c - image) * (ds / (ds + dr))) : Vec3(0.5 * (s_c + r_c));
    int tri = -1;
    for (int t : pl.triangles) {
      if (opening_[room_.mesh.object_of_triangle[t]]) continue;
      const auto& v = room_.mesh.triangles[t];
      if (insideTriangle(p, room_.mesh.vertices[v[0]], room_.mesh.vertices[v[1]], room_.mesh.vertices[v[2]])) {
        tri = t;
        break;
      }
    }
    if (tri < 0) continue;
    if (crossesSurfaceAt(pl, p, s, r)) continue;
    // Visibility only: the reflection point and any point on the plane are lifted by the offset into the air.
    const Vec3 lift = side * offsetAt(p) * pl.normal;
    const Vec3 lifted = p + lift;
    if (!visible(s_on ? Vec3(s_c - ds * pl.normal + lift) : s, lifted) ||
        !visible(lifted, r_on ? Vec3(r_c - dr * pl.normal + lift) : r))
      continue;
    out.push_back(reflectionPath(tri, s, p, r, (r_c - image).norm(), 1.0));
  }
}

void UtdModel::addFirstOrder(const Vec3& s, const Vec3& r, std::vector<Path>& out) const {
  for (int e = 0; e < static_cast<int>(edges_.size()); ++e) {
    double arc;
    if (!apexOnEdge(edges_[e], s, r, arc)) continue;
    const Vec3 q = edges_[e].at(arc);
    const double s_in = (q - s).norm(), s_out = (r - q).norm();
    Diffraction d;
    if (!(s_in > 0.0 && s_out > 0.0) || !diffraction(e, q, s, r, s_in * s_out / (s_in + s_out), d)) continue;
    const Vec3 q_air = offEdge(e, q);
    if (!visible(s, q_air) || !visible(q_air, r)) continue;
    Path path;
    path.kind = PathKind::Diffraction;
    path.order = 1;
    path.edges = {e};
    path.diffractions = {d};
    path.points = {s, q, r};
    path.length_m = s_in + s_out;
    out.push_back(std::move(path));
  }
}

void UtdModel::addSecondOrder(const Vec3& s, const Vec3& r, std::vector<Path>& out) const {
  const int n = static_cast<int>(edges_.size());
  for (int e1 = 0; e1 < n; ++e1) {
    for (int e2 = 0; e2 < n; ++e2) {
      const bool collinear = edges_[e1].tangent.cross(edges_[e2].tangent).norm() < 1e-9 &&
                             (edges_[e2].start - edges_[e1].start).cross(edges_[e1].tangent).norm() < offsetAt(edges_[e2].start);
      if (e1 == e2 || collinear) continue;  // the same edge, or collinear pieces: no path between them leaves the line
      double a1, a2;
      if (!apexesOnEdges(edges_[e1], edges_[e2], s, r, a1, a2)) continue;
      const Vec3 q1 = edges_[e1].at(a1), q2 = edges_[e2].at(a2);
      const double s0 = (q1 - s).norm(), s1 = (q2 - q1).norm(), s2 = (r - q2).norm();
      if (!(s0 > 0.0 && s1 > offsetAt(q1) && s2 > 0.0)) continue;
      const double rho = s0 + s1;
      Diffraction d1, d2;
      if (!diffraction(e1, q1, s, q2, s0 * s1 / (s0 + s1), d1) || !diffraction(e2, q2, q1, r, rho * s2 / (rho + s2), d2))
        continue;
      const Vec3 q1_air = offEdge(e1, q1), q2_air = offEdge(e2, q2);
      if (!visible(s, q1_air) || !visible(q1_air, q2_air) || !visible(q2_air, r)) continue;
      Path path;
      path.kind = PathKind::Diffraction;
      path.order = 2;
      path.edges = {e1, e2};
      path.diffractions = {d1, d2};
      path.points = {s, q1, q2, r};
      path.length_m = s0 + s1 + s2;
      out.push_back(std::move(path));
    }
  }
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
  if (options_.max_order >= 1) addFirstOrder(source, listener, out);
  // A listener on a shadow boundary of an edge: the incident one (φ = φ′ ± π) or the reflection one of face 0
  // (φ + φ′ = π) or face n (φ + φ′ = (2n − 1)π). Embree's visibility of the ray grazing the edge, and the
  // triangle test of a reflection point on the edge, are decided by rounding, while the diffracted term
  // takes the mean of its two sides (coefficient.h): the geometric field there is half of the full one,
  // whatever the tests said (Kouyoumjian & Pathak 1974).
  const double tol = kBoundaryTolRad;
  bool on_boundary = false;
  std::vector<std::pair<int, int>> reflection_boundaries;  // (edge, face: 0 or 1 for face n)
  for (const Path& p : out) {
    if (p.kind != PathKind::Diffraction || p.order != 1) continue;
    const Diffraction& d = p.diffractions[0];
    if (std::abs(std::abs(d.phi_out - d.phi_in) - core::kPi) < tol) on_boundary = true;
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
  if (options_.reflections)
    for (const auto& [e, face] : reflection_boundaries) halveReflection(e, face, source, listener, out);
  if (options_.max_order >= 2) addSecondOrder(source, listener, out);
  return out;
}

void UtdModel::halveReflection(int e, int face, const Vec3& s, const Vec3& r, std::vector<Path>& out) const {
  const Edge& edge = edges_[e];
  const int face_tri = face == 0 ? edge.triangle0 : edge.trianglen;
  const Vec3& normal = face == 0 ? edge.normal0 : edge.normaln;
  if (face_tri < 0) return;
  const int plane = geometry_.triangle(face_tri).plane;
  for (Path& p : out) {
    if (p.kind == PathKind::Reflection && geometry_.triangle(p.triangle).plane == plane) {
      p.gain = 0.5;
      return;
    }
  }
  // The triangle test missed the reflection point, which lies on the edge: add the path, with the face's
  // triangle for its material. The listener sees the image of s in the face plane through the edge.
  const double ds = normal.dot(s - edge.start), dr = normal.dot(r - edge.start);
  if (!(ds + dr > 0.0)) return;  // both on the face's plane: no distinct reflection
  const Vec3 image = s - 2.0 * ds * normal;
  const Vec3 q = image + (r - image) * (ds / (ds + dr));
  out.push_back(reflectionPath(face_tri, s, q, r, (r - image).norm(), 0.5));
}

std::complex<double> UtdModel::pressure(const Path& path, double freq_hz, double c_m_s) const {
  core::requirePositive("utd frequency", freq_hz);
  core::requirePositive("utd speed of sound", c_m_s);
  const double k = core::kTwoPi * freq_hz / c_m_s;
  const cd phase = std::exp(cd(0.0, -k * path.length_m));
  if (path.kind == PathKind::Direct) return path.gain * phase / path.length_m;
  if (path.kind == PathKind::Reflection)
    return path.gain * faceReflection(room_.mesh.object_of_triangle[path.triangle], freq_hz) * phase / path.length_m;
  // Diffraction: (1/s′)·Π D_i·A_i·e^{−ik·length}, A_i = √(ρ_i/(s_i(ρ_i + s_i))), ρ_i the unfolded distance
  // from the source to apex i and s_i the leg after it (to the next apex or the listener).
  cd p = phase / (path.points[1] - path.points[0]).norm();
  double rho = 0.0;
  for (std::size_t i = 0; i < path.diffractions.size(); ++i) {
    const Diffraction& d = path.diffractions[i];
    const Edge& e = edges_[d.edge];
    rho += (path.points[i + 1] - path.points[i]).norm();
    const double s = (path.points[i + 2] - path.points[i + 1]).norm();
    const FaceReflection r{faceReflection(e.material0, freq_hz), faceReflection(e.materialn, freq_hz)};
    cd dc = wedgeCoefficient(e.wedge_n, k, d.l_m, d.phi_out, d.phi_in, d.beta0, r);
    if (d.grazing) dc *= 0.5;
    p *= dc * std::sqrt(rho / (s * (rho + s)));
  }
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
