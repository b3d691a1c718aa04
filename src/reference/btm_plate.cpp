// A thin rigid plate's field to first order in edge diffraction (see btm_plate.h).
#include "diffray/reference/btm_plate.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/reference/btm_edge.h"
#include "diffray/reference/btm_kernel.h"
#include "diffray/reference/band_grid.h"

namespace diffray::reference {
namespace {

using Complex = std::complex<double>;
using core::Vec3;

constexpr double kPi = 3.14159265358979323846;

// The plate's unit normal (Newell's method), centroid and scale, after checking it is a convex planar
// polygon.
struct PlateFrame {
  Vec3 normal, centroid;
  double scale = 0.0;
};

PlateFrame checkPlate(const BtmPlate& plate) {
  const std::size_t n = plate.vertices.size();
  if (n < 3) throw core::InputError("plate", "needs at least 3 vertices, got " + std::to_string(n));
  PlateFrame f;
  f.normal = Vec3::Zero();
  f.centroid = Vec3::Zero();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& a = plate.vertices[i];
    const Vec3& b = plate.vertices[(i + 1) % n];
    for (int c = 0; c < 3; ++c) core::requireFinite("plate vertex", a[c]);
    f.normal += a.cross(b);
    f.centroid += a / static_cast<double>(n);
  }
  for (const Vec3& v : plate.vertices) f.scale = std::max(f.scale, (v - f.centroid).norm());
  const double twice_area = f.normal.norm();
  if (!(twice_area > 1e-12 * f.scale * f.scale)) throw core::InputError("plate", "has no area");
  f.normal /= twice_area;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& a = plate.vertices[i];
    if (std::abs((a - f.centroid).dot(f.normal)) > 1e-9 * f.scale)
      throw core::InputError("plate", "vertex " + std::to_string(i) + " is off the plate's plane");
    const Vec3 turn = (plate.vertices[(i + 1) % n] - a).cross(plate.vertices[(i + 2) % n] - plate.vertices[(i + 1) % n]);
    if (turn.dot(f.normal) < -1e-12 * f.scale * f.scale)
      throw core::InputError("plate", "is not convex at vertex " + std::to_string((i + 1) % n));
    // Two edges in line would be one edge split in two (the edge-to-edge term between them is undefined).
    if (turn.dot(f.normal) <= 1e-12 * f.scale * f.scale)
      throw core::InputError("plate", "vertex " + std::to_string((i + 1) % n) + " lies in line with its neighbours");
  }
  return f;
}

// Whether the point p of the plate's plane lies inside the polygon (convex: left of every edge).
bool insidePolygon(const BtmPlate& plate, const PlateFrame& f, const Vec3& p) {
  const std::size_t n = plate.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& a = plate.vertices[i];
    const Vec3& b = plate.vertices[(i + 1) % n];
    if ((b - a).cross(p - a).dot(f.normal) < 0.0) return false;
  }
  return true;
}

// Where the segment from p to q crosses the plate's plane, if its ends lie strictly on opposite sides.
bool crossesPlane(const PlateFrame& f, const Vec3& p, const Vec3& q, Vec3* at) {
  const double dp = (p - f.centroid).dot(f.normal), dq = (q - f.centroid).dot(f.normal);
  if (!(dp * dq < 0.0)) return false;
  *at = p + (q - p) * (dp / (dp - dq));
  return true;
}

// An edge's frame (btm_plate.h): origin at its first vertex, z along it, x into the plate, y = the normal.
struct EdgeFrame {
  Vec3 origin, x, y, z;
  double length = 0.0;
  CylindricalPoint of(const Vec3& p) const {
    const Vec3 d = p - origin;
    double theta = std::atan2(d.dot(y), d.dot(x));
    if (theta < 0.0) theta += 2.0 * kPi;
    return {std::hypot(d.dot(x), d.dot(y)), theta, d.dot(z)};
  }
};

std::vector<EdgeFrame> edgeFrames(const BtmPlate& plate, const PlateFrame& f) {
  std::vector<EdgeFrame> frames;
  const std::size_t n = plate.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    EdgeFrame e;
    e.origin = plate.vertices[i];
    const Vec3 along = plate.vertices[(i + 1) % n] - e.origin;
    e.length = along.norm();
    e.z = along / e.length;
    e.x = f.normal.cross(e.z);  // in the plane, into the polygon (counter-clockwise about the normal)
    e.y = e.z.cross(e.x);       // the normal
    frames.push_back(e);
  }
  return frames;
}

// u₂ of the ordered pair (ei, ej) for the path along the face at azimuth `face` (0 or 2π): see the header.
// The inner integral over edge j is graded toward the apex of P_i and R on it; the outer one over edge i
// toward a corner the two edges share (where n → 0), else from edge i's middle.
Complex edgePair(double k, const EdgeFrame& ei, const EdgeFrame& ej, double face, const Vec3& source,
                 const Vec3& receiver, double scale) {
  const double nu = 0.5, wavelength = 2.0 * kPi / k;
  const CylindricalPoint s = ei.of(source), r = ej.of(receiver);
  const BtmBeta beta_i(nu, s.phi_rad, face), beta_j(nu, face, r.phi_rad);
  double corner_j = -1.0;  // where on edge j a corner shared with edge i lies (set below), else −1
  const auto inner = [&](double zi) {
    const Vec3 pi = ei.origin + zi * ei.z;
    const CylindricalPoint pi_j = ej.of(pi);  // P_i in edge j's frame
    const double a_i = zi - s.z_m, m = std::hypot(s.rho_m, a_i);
    const auto g = [&](double zj) {
      const Vec3 pj = ej.origin + zj * ej.z;
      const CylindricalPoint pj_i = ei.of(pj);  // P_j in edge i's frame
      const double b_i = zi - pj_i.z_m, n = std::hypot(pj_i.rho_m, b_i);
      const double a_j = zj - pi_j.z_m, b_j = zj - r.z_m, l = std::hypot(r.rho_m, b_j);
      const double bi = beta_i(s.rho_m, pj_i.rho_m, a_i, b_i, m, n);
      const double bj = beta_j(pi_j.rho_m, r.rho_m, a_j, b_j, n, l);
      return std::polar(bi * bj / (m * n * l), -k * (m + n + l));
    };
    const double apex = std::clamp(pi_j.z_m + (r.z_m - pi_j.z_m) * pi_j.rho_m / (pi_j.rho_m + r.rho_m), 0.0, ej.length);
    const double first_j = beta_j.firstPanel(pi_j.rho_m, r.rho_m, scale);
    if (corner_j < 0.0) return btmGradedIntegral(g, apex, 0.0, ej.length, scale, wavelength, first_j);
    // Near the shared corner n varies on the scale of P_i's distance from it: grade toward the corner too.
    const double split = 0.5 * (apex + corner_j);
    const double other_end = corner_j == 0.0 ? ej.length : 0.0;
    return btmGradedIntegral(g, corner_j, std::min(corner_j, split), std::max(corner_j, split), scale, wavelength, 1e-8 * scale) +
           btmGradedIntegral(g, apex, std::min(split, other_end), std::max(split, other_end), scale, wavelength, first_j);
  };
  double corner_i = 0.5 * ei.length;
  const double touch = 1e-9 * scale;
  if ((ei.origin + ei.length * ei.z - ej.origin).norm() < touch) corner_i = ei.length, corner_j = 0.0;
  else if ((ei.origin - (ej.origin + ej.length * ej.z)).norm() < touch) corner_i = 0.0, corner_j = ej.length;
  const Complex integral = btmGradedIntegral(inner, corner_i, 0.0, ei.length, scale, wavelength, 1e-8 * scale);
  return 0.5 * (nu * nu / (16.0 * kPi * kPi)) * integral;
}

Complex spherical(double k, double r) { return std::polar(1.0 / r, -k * r); }

}  // namespace

BtmPlateField btmPlateField(double wavenumber_rad_m, const BtmPlate& plate, const Vec3& source, const Vec3& receiver,
                            int order) {
  if (order != 1 && order != 2) throw core::InputError("order", "must be 1 or 2, got " + std::to_string(order));
  const PlateFrame f = checkPlate(plate);
  for (int c = 0; c < 3; ++c) {
    core::requireFinite("source", source[c]);
    core::requireFinite("receiver", receiver[c]);
  }
  const double ds = (source - f.centroid).dot(f.normal), dr = (receiver - f.centroid).dot(f.normal);
  const double on_plane = 1e-12 * f.scale;
  if (std::abs(ds) <= on_plane && insidePolygon(plate, f, source)) throw core::InputError("source", "lies on the plate");
  if (std::abs(dr) <= on_plane && insidePolygon(plate, f, receiver)) throw core::InputError("receiver", "lies on the plate");
  BtmPlateField u;
  Vec3 at;
  if (!(crossesPlane(f, source, receiver, &at) && insidePolygon(plate, f, at)))
    u.direct = spherical(wavenumber_rad_m, (receiver - source).norm());
  if (ds * dr > 0.0) {
    const Vec3 image = source - 2.0 * ds * f.normal;
    if (crossesPlane(f, image, receiver, &at) && insidePolygon(plate, f, at))
      u.specular = spherical(wavenumber_rad_m, (receiver - image).norm());
  }
  const std::vector<EdgeFrame> edges = edgeFrames(plate, f);
  for (const EdgeFrame& e : edges) {
    BtmWedge edge;
    edge.exterior_angle_rad = 2.0 * kPi;
    edge.z_start_m = 0.0;
    edge.z_end_m = e.length;
    u.diffracted += btmEdgeDiffraction(wavenumber_rad_m, edge, e.of(source), e.of(receiver));
  }
  if (order >= 2) {
    const double scale = f.scale + (source - f.centroid).norm() + (receiver - f.centroid).norm();
    for (std::size_t i = 0; i < edges.size(); ++i)
      for (std::size_t j = 0; j < edges.size(); ++j)
        if (i != j)
          for (double face : {0.0, 2.0 * kPi})
            u.second_order += edgePair(wavenumber_rad_m, edges[i], edges[j], face, source, receiver, scale);
  }
  return u;
}

BtmPlateField btmPlateOnGroundField(double wavenumber_rad_m, const BtmPlate& plate, double ground_z_m,
                                    const Vec3& source, const Vec3& receiver, int order) {
  core::requireFinite("ground height", ground_z_m);
  const PlateFrame f = checkPlate(plate);
  const double tol = 1e-9 * std::max(1.0, f.scale + std::abs(ground_z_m));
  if (std::abs(f.normal.z()) > 1e-9) throw core::InputError("plate", "must stand perpendicular to the ground");
  const std::size_t n = plate.vertices.size();
  std::size_t foot = n;  // the edge (foot, foot + 1) on the ground
  for (std::size_t i = 0; i < n; ++i) {
    if (plate.vertices[i].z() < ground_z_m - tol) throw core::InputError("plate", "reaches below the ground");
    if (std::abs(plate.vertices[i].z() - ground_z_m) <= tol && std::abs(plate.vertices[(i + 1) % n].z() - ground_z_m) <= tol)
      foot = i;
  }
  if (foot == n) throw core::InputError("plate", "has no edge on the ground (z = " + std::to_string(ground_z_m) + ")");
  if (!(source.z() > ground_z_m + tol) || !(receiver.z() > ground_z_m + tol))
    throw core::InputError("ground", "the source and the receiver must lie above it");
  // The union: from the foot's second vertex round the plate to its first, then the mirror images of the
  // vertices above the ground in reverse order (a convex polygon: the foot edge is straight, the plate is
  // perpendicular to the ground).
  const auto mirror = [ground_z_m](const Vec3& v) { return Vec3(v.x(), v.y(), 2.0 * ground_z_m - v.z()); };
  BtmPlate both;
  for (std::size_t k = 0; k < n; ++k) both.vertices.push_back(plate.vertices[(foot + 1 + k) % n]);
  for (std::size_t k = n - 1; k-- > 1;) both.vertices.push_back(mirror(plate.vertices[(foot + 1 + k) % n]));
  // A ground vertex whose two edges meet the ground at right angles now lies in line with its neighbours.
  for (std::size_t i = 0; i < both.vertices.size() && both.vertices.size() > 3;) {
    const std::size_t m = both.vertices.size();
    const Vec3 &a = both.vertices[(i + m - 1) % m], &b = both.vertices[i], &c = both.vertices[(i + 1) % m];
    if ((b - a).cross(c - b).norm() <= 1e-12 * (b - a).norm() * (c - b).norm()) both.vertices.erase(both.vertices.begin() + static_cast<long>(i));
    else ++i;
  }
  const BtmPlateField direct = btmPlateField(wavenumber_rad_m, both, source, receiver, order);
  const BtmPlateField image = btmPlateField(wavenumber_rad_m, both, mirror(source), receiver, order);
  BtmPlateField u;
  u.direct = direct.direct + image.direct;
  u.specular = direct.specular + image.specular;
  u.diffracted = direct.diffracted + image.diffracted;
  u.second_order = direct.second_order + image.second_order;
  return u;
}

double btmPlateBandLevelDb(double f_lo_hz, double f_hi_hz, int points, double sound_speed_m_s, const BtmPlate& plate,
                           double ground_z_m, const Vec3& source, const Vec3& receiver, int order) {
  core::requirePositive("speed of sound", sound_speed_m_s);
  const std::vector<double> grid = bandGridHz("btmPlateBandLevelDb", f_lo_hz, f_hi_hz, points);
  const double r = (receiver - source).norm();
  double energy = 0.0;
  for (double hz : grid) {
    const double k = 2.0 * kPi * hz / sound_speed_m_s;
    const BtmPlateField u = std::isnan(ground_z_m) ? btmPlateField(k, plate, source, receiver, order)
                                                   : btmPlateOnGroundField(k, plate, ground_z_m, source, receiver, order);
    energy += std::norm(u.total() * r);
  }
  return 10.0 * std::log10(energy / static_cast<double>(grid.size()));
}

}  // namespace diffray::reference
