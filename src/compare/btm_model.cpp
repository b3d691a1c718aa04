// compare's BTM exact model for a rigid plate, free or on a rigid ground (see btm_model.h).
#include "diffray/compare/btm_model.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

#include "diffray/reference/btm_spectrum.h"

namespace diffray::compare {

using core::Vec3;

namespace {

constexpr double kPi = 3.14159265358979323846;

class BtmPlateModel : public PointModel {
 public:
  BtmPlateModel(reference::BtmPlate plate, double ground_z, double c, double f_max)
      : plate_(std::move(plate)), ground_z_(ground_z), c_(c), f_max_(f_max) {}
  std::string name() const override { return "exact"; }
  std::vector<std::complex<double>> relativePressure(const Vec3& s, const Vec3& l, const std::vector<double>& f) const override {
    const std::complex<double> none(std::nan(""), std::nan(""));
    std::vector<std::complex<double>> out(f.size(), none);
    std::vector<double> k;
    std::vector<std::size_t> at;
    for (std::size_t j = 0; j < f.size(); ++j)
      if (f[j] <= f_max_) {
        k.push_back(2.0 * kPi * f[j] / c_);
        at.push_back(j);
      }
    if (k.empty()) return out;
    const std::vector<reference::BtmPlateField> u = reference::btmPlateSpectrum(k, plate_, ground_z_, s, l, 2);
    const double r = (l - s).norm();
    // p/p_free = u·R·e^{ikR} (time factor e^{iωt}).
    for (std::size_t i = 0; i < at.size(); ++i) out[at[i]] = u[i].total() * std::polar(r, k[i] * r);
    return out;
  }

 private:
  reference::BtmPlate plate_;
  double ground_z_, c_, f_max_;
};

// The distinct vertices of the triangles of `group`, in order around their centroid (a convex polygon).
std::vector<Vec3> groupPolygon(const room::Room& room, const std::string& group) {
  std::vector<Vec3> points;
  for (std::size_t t = 0; t < room.mesh.triangles.size(); ++t) {
    if (room.group_of_triangle[t] != group) continue;
    for (int v : room.mesh.triangles[t]) {
      const Vec3& p = room.mesh.vertices[static_cast<std::size_t>(v)];
      if (std::none_of(points.begin(), points.end(), [&](const Vec3& q) { return (q - p).norm() <= 1e-9 * (1.0 + p.norm()); }))
        points.push_back(p);
    }
  }
  if (points.size() < 3) return points;
  Vec3 centroid = Vec3::Zero();
  for (const Vec3& p : points) centroid += p / static_cast<double>(points.size());
  const Vec3 u = (points[0] - centroid).normalized();
  const Vec3 n = u.cross(points[1] - centroid).normalized(), w = n.cross(u);
  std::sort(points.begin(), points.end(), [&](const Vec3& a, const Vec3& b) {
    return std::atan2((a - centroid).dot(w), (a - centroid).dot(u)) < std::atan2((b - centroid).dot(w), (b - centroid).dot(u));
  });
  return points;
}

bool rigid(const room::Room& room, int material) {
  for (int b = 0; b < room.bands.size(); ++b)
    if (room.materials[static_cast<std::size_t>(material)].absorption[static_cast<std::size_t>(b)] != 0.0) return false;
  return true;
}

}  // namespace

std::unique_ptr<PointModel> btmModelFor(const room::Room& room, double c, std::string& why_not, std::string& assumption) {
  if (room.occluders.size() != 1 || room.occluders[0].type != "barrier") {
    why_not = "the BTM reference fits one barrier";
    return nullptr;
  }
  const room::Occluder& o = room.occluders[0];
  const std::string group = "barrier:" + o.name;
  if (o.x.faces == room::OccluderAxis::Faces::Soft) {
    why_not = "the BTM reference is for rigid plates; barrier " + o.name + " has soft faces";
    return nullptr;
  }
  reference::BtmPlate plate{groupPolygon(room, group)};
  double foot = 1e300;
  for (const Vec3& v : plate.vertices) foot = std::min(foot, v.z());
  bool plate_rigid = true, ground = false, ground_rigid = true;
  for (std::size_t t = 0; t < room.mesh.triangles.size(); ++t) {
    const int material = room.mesh.object_of_triangle[t];
    if (room.isOpening(material)) continue;  // the occluder's own zone: it transmits everything
    if (room.group_of_triangle[t] == group) {
      plate_rigid = plate_rigid && rigid(room, material);
      continue;
    }
    ground = true;
    for (int v : room.mesh.triangles[t])
      if (std::abs(room.mesh.vertices[static_cast<std::size_t>(v)].z() - foot) > 1e-9 * (1.0 + std::abs(foot))) {
        why_not = "the BTM reference fits a barrier in free field or on a flat ground at its foot; triangle " +
                  std::to_string(t) + " (" + room.group_of_triangle[t] + ") is elsewhere";
        return nullptr;
      }
    ground_rigid = ground_rigid && rigid(room, material);
  }
  if (!plate_rigid || !ground_rigid) {
    why_not = std::string("the BTM reference is for rigid surfaces (absorption 0 in every band); the ") +
              (plate_rigid ? "ground" : "barrier's panel") + " absorbs";
    return nullptr;
  }
  if (plate.vertices.size() < 3) {
    why_not = "barrier " + o.name + " has no panel in the mesh";
    return nullptr;
  }
  // The perimeter; on a ground the plate joined with its mirror image: every edge but the foot, twice.
  double perimeter = 0.0, foot_edge = 0.0;
  const std::size_t n = plate.vertices.size();
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 &a = plate.vertices[i], &b = plate.vertices[(i + 1) % n];
    perimeter += (b - a).norm();
    if (std::max(a.z(), b.z()) - foot <= 1e-9 * (1.0 + std::abs(foot))) foot_edge = (b - a).norm();
  }
  if (ground) {
    const Vec3 normal = (plate.vertices[1] - plate.vertices[0]).cross(plate.vertices[2] - plate.vertices[1]).normalized();
    if (std::abs(normal.z()) > 1e-9 || foot_edge == 0.0) {
      why_not = "the BTM reference on a ground needs the barrier standing upright on it (\"up\" perpendicular to the ground)";
      return nullptr;
    }
    perimeter = 2.0 * (perimeter - foot_edge);
  }
  const double f_max = kBtmMaxPerimeterWavelengths * c / perimeter;
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "exact: BTM edge diffraction to second order (Svensson et al. 1999) of the rigid plate of barrier %s%s, "
                "up to %.0f Hz (the plate's perimeter%s up to %.0f wavelengths)",
                o.name.c_str(), ground ? " on a rigid ground (image principle)" : " in free field", f_max,
                ground ? ", its ground mirror included," : "", kBtmMaxPerimeterWavelengths);
  assumption = buf;
  return std::make_unique<BtmPlateModel>(std::move(plate), ground ? foot : std::nan(""), c, f_max);
}

}  // namespace diffray::compare
