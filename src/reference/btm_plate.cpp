// A thin rigid plate's field to first order in edge diffraction (see btm_plate.h).
#include "diffray/reference/btm_plate.h"

#include <cmath>
#include <string>

#include "diffray/core/error.h"
#include "diffray/reference/btm_edge.h"

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

CylindricalPoint edgeFrame(const Vec3& origin, const Vec3& x, const Vec3& y, const Vec3& z, const Vec3& p) {
  const Vec3 d = p - origin;
  double theta = std::atan2(d.dot(y), d.dot(x));
  if (theta < 0.0) theta += 2.0 * kPi;
  return {std::hypot(d.dot(x), d.dot(y)), theta, d.dot(z)};
}

Complex spherical(double k, double r) { return std::polar(1.0 / r, -k * r); }

}  // namespace

BtmPlateField btmPlateField(double wavenumber_rad_m, const BtmPlate& plate, const Vec3& source, const Vec3& receiver) {
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
  const std::size_t n = plate.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& a = plate.vertices[i];
    const Vec3& b = plate.vertices[(i + 1) % n];
    const double length = (b - a).norm();
    const Vec3 z = (b - a) / length;
    const Vec3 x = f.normal.cross(z);  // in the plane, pointing into the polygon (counter-clockwise about n)
    const Vec3 y = z.cross(x);
    BtmWedge edge;
    edge.exterior_angle_rad = 2.0 * kPi;
    edge.z_start_m = 0.0;
    edge.z_end_m = length;
    u.diffracted += btmEdgeDiffraction(wavenumber_rad_m, edge, edgeFrame(a, x, y, z, source), edgeFrame(a, x, y, z, receiver));
  }
  return u;
}

}  // namespace diffray::reference
