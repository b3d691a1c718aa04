// A thin rigid plate's field to second order in edge diffraction (see btm_plate.h), and the plate's
// geometry and paths (btm_plate_paths.h).
#include "diffray/reference/btm_plate.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "btm_plate_paths.h"
#include "diffray/core/error.h"
#include "diffray/reference/band_grid.h"
#include "diffray/reference/btm_kernel.h"
#include "diffray/reference/btm_spectrum.h"

namespace diffray::reference {
namespace btm_detail {

using core::Vec3;

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

bool insidePolygon(const BtmPlate& plate, const PlateFrame& f, const Vec3& p) {
  const std::size_t n = plate.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3& a = plate.vertices[i];
    const Vec3& b = plate.vertices[(i + 1) % n];
    if ((b - a).cross(p - a).dot(f.normal) < 0.0) return false;
  }
  return true;
}

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

GeometricPaths geometricPaths(const BtmPlate& plate, const PlateFrame& f, const std::vector<EdgeFrame>& edges,
                              const Vec3& source, const Vec3& receiver) {
  for (int c = 0; c < 3; ++c) {
    core::requireFinite("source", source[c]);
    core::requireFinite("receiver", receiver[c]);
  }
  const double ds = (source - f.centroid).dot(f.normal), dr = (receiver - f.centroid).dot(f.normal);
  const double on_plane = 1e-12 * f.scale;
  if (std::abs(ds) <= on_plane && insidePolygon(plate, f, source)) throw core::InputError("source", "lies on the plate");
  if (std::abs(dr) <= on_plane && insidePolygon(plate, f, receiver)) throw core::InputError("receiver", "lies on the plate");
  // How far the line from p to q, which crosses the plate's plane, passes beside the plate, as an angle: the
  // largest over the edges of π − |θq − θp| (azimuths about each edge, x into the plate). Positive where
  // the line crosses the plane beyond that edge, negative where it crosses the plate, 0 on an edge's line.
  const auto passMargin = [&](const Vec3& p, const Vec3& q) {
    double m = -kPi;
    for (const EdgeFrame& e : edges) m = std::max(m, kPi - std::abs(e.of(q).phi_rad - e.of(p).phi_rad));
    return m;
  };
  const auto weight = [](double margin) {
    return margin > kBtmOnBoundaryRad ? 1.0 : (margin < -kBtmOnBoundaryRad ? 0.0 : 0.5);
  };
  GeometricPaths paths{{(receiver - source).norm(), 1.0}, {0.0, 0.0}};
  if (ds * dr < 0.0) paths.direct.weight = weight(passMargin(source, receiver));
  if (ds * dr > 0.0) {
    const Vec3 image = source - 2.0 * ds * f.normal;
    paths.specular = {(receiver - image).norm(), weight(-passMargin(image, receiver))};
  }
  return paths;
}

BtmPlate groundUnion(const BtmPlate& plate, double ground_z_m, const Vec3& source, const Vec3& receiver) {
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
  BtmPlate both;
  for (std::size_t k = 0; k < n; ++k) both.vertices.push_back(plate.vertices[(foot + 1 + k) % n]);
  for (std::size_t k = n - 1; k-- > 1;) {
    const Vec3& v = plate.vertices[(foot + 1 + k) % n];
    both.vertices.emplace_back(v.x(), v.y(), 2.0 * ground_z_m - v.z());
  }
  // A ground vertex whose two edges meet the ground at right angles now lies in line with its neighbours.
  for (std::size_t i = 0; i < both.vertices.size() && both.vertices.size() > 3;) {
    const std::size_t m = both.vertices.size();
    const Vec3 &a = both.vertices[(i + m - 1) % m], &b = both.vertices[i], &c = both.vertices[(i + 1) % m];
    if ((b - a).cross(c - b).norm() <= 1e-12 * (b - a).norm() * (c - b).norm()) both.vertices.erase(both.vertices.begin() + static_cast<long>(i));
    else ++i;
  }
  return both;
}

std::vector<BtmNode> firstOrderNodes(const std::vector<EdgeFrame>& edges, const Vec3& source, const Vec3& receiver,
                                     double wavelength_m) {
  std::vector<BtmNode> nodes;
  for (const EdgeFrame& e : edges) {
    BtmWedge edge;
    edge.exterior_angle_rad = 2.0 * kPi;
    edge.z_start_m = 0.0;
    edge.z_end_m = e.length;
    btmEdgeNodes(edge, e.of(source), e.of(receiver), wavelength_m, &nodes);
  }
  return nodes;
}

}  // namespace btm_detail

using namespace btm_detail;

namespace {
std::complex<double> spherical(double k, const GeometricWave& w) {
  return w.weight > 0.0 ? std::polar(w.weight / w.path_m, -k * w.path_m) : std::complex<double>(0.0, 0.0);
}
}  // namespace

BtmPlateField btmPlateField(double wavenumber_rad_m, const BtmPlate& plate, const Vec3& source, const Vec3& receiver,
                            int order) {
  if (order != 1 && order != 2) throw core::InputError("order", "must be 1 or 2, got " + std::to_string(order));
  core::requireFinite("wavenumber", wavenumber_rad_m);
  if (!(wavenumber_rad_m > 0.0)) throw core::InputError("wavenumber", "must be > 0, got " + std::to_string(wavenumber_rad_m));
  const PlateFrame f = checkPlate(plate);
  const std::vector<EdgeFrame> edges = edgeFrames(plate, f);
  const GeometricPaths paths = geometricPaths(plate, f, edges, source, receiver);
  const double k = wavenumber_rad_m, wavelength = 2.0 * kPi / k;
  BtmPlateField u;
  u.direct = spherical(k, paths.direct);
  u.specular = spherical(k, paths.specular);
  for (const BtmNode& q : firstOrderNodes(edges, source, receiver, wavelength)) u.diffracted += std::polar(q.amplitude, -k * q.path_m);
  if (order >= 2) {
    const double scale = pairScale(f, source, receiver);
    const auto add = [&](double path, double amplitude) { u.second_order += std::polar(amplitude, -k * path); };
    for (std::size_t i = 0; i < edges.size(); ++i)
      for (std::size_t j = 0; j < edges.size(); ++j)
        if (i != j) edgePairNodes(edges[i], edges[j], plateFaces(edges[i]), source, receiver, scale, wavelength, add);
  }
  return u;
}

BtmPlateField btmPlateOnGroundField(double wavenumber_rad_m, const BtmPlate& plate, double ground_z_m,
                                    const Vec3& source, const Vec3& receiver, int order) {
  const BtmPlate both = groundUnion(plate, ground_z_m, source, receiver);
  const Vec3 image(source.x(), source.y(), 2.0 * ground_z_m - source.z());
  const BtmPlateField direct = btmPlateField(wavenumber_rad_m, both, source, receiver, order);
  const BtmPlateField mirrored = btmPlateField(wavenumber_rad_m, both, image, receiver, order);
  BtmPlateField u;
  u.direct = direct.direct + mirrored.direct;
  u.specular = direct.specular + mirrored.specular;
  u.diffracted = direct.diffracted + mirrored.diffracted;
  u.second_order = direct.second_order + mirrored.second_order;
  return u;
}

double btmPlateBandLevelDb(double f_lo_hz, double f_hi_hz, int points, double sound_speed_m_s, const BtmPlate& plate,
                           double ground_z_m, const Vec3& source, const Vec3& receiver, int order) {
  core::requirePositive("speed of sound", sound_speed_m_s);
  const std::vector<double> grid = bandGridHz("btmPlateBandLevelDb", f_lo_hz, f_hi_hz, points);
  std::vector<double> wavenumbers;
  for (double hz : grid) wavenumbers.push_back(2.0 * kPi * hz / sound_speed_m_s);
  const double r = (receiver - source).norm();
  double energy = 0.0;
  for (const BtmPlateField& u : btmPlateSpectrum(wavenumbers, plate, ground_z_m, source, receiver, order))
    energy += std::norm(u.total() * r);
  return 10.0 * std::log10(energy / static_cast<double>(grid.size()));
}

}  // namespace diffray::reference
