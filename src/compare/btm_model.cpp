// compare's BTM exact model for a rigid plate or a rigid box, free or on a rigid ground (see btm_model.h).
#include "diffray/compare/btm_model.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/reference/btm_box.h"
#include "diffray/reference/btm_spectrum.h"
#include "diffray/room/json_fields.h"
#include "diffray/room/occluder_file.h"

namespace diffray::compare {

using core::Vec3;

namespace {

constexpr double kPi = 3.14159265358979323846;

// The part common to both objects: the frequencies up to the size limit handed to the reference at once,
// its total field made relative to the free field, p/p_free = u·R·e^{ikR} (time factor e^{iωt}), NaN above.
class BtmModel : public PointModel {
 public:
  BtmModel(double ground_z, double c, double f_max) : ground_z_(ground_z), c_(c), f_max_(f_max) {}
  std::string name() const override { return "exact"; }
  std::vector<std::complex<double>> relativePressure(const Vec3& s, const Vec3& l, const std::vector<double>& f) const override {
    std::vector<std::complex<double>> out(f.size(), std::complex<double>(std::nan(""), std::nan("")));
    std::vector<double> k;
    std::vector<std::size_t> at;
    for (std::size_t j = 0; j < f.size(); ++j)
      if (f[j] <= f_max_) {
        k.push_back(2.0 * kPi * f[j] / c_);
        at.push_back(j);
      }
    if (k.empty()) return out;
    const std::vector<reference::BtmField> u = spectrum(k, s, l);
    const double r = (l - s).norm();
    for (std::size_t i = 0; i < at.size(); ++i) out[at[i]] = u[i].total() * std::polar(r, k[i] * r);
    return out;
  }

 protected:
  /// The reference's field at each wavenumber, on the ground ground_z_ (NaN: none).
  virtual std::vector<reference::BtmField> spectrum(const std::vector<double>& k, const Vec3& s, const Vec3& l) const = 0;
  double ground_z_;

 private:
  double c_, f_max_;
};

class BtmPlateModel : public BtmModel {
 public:
  BtmPlateModel(reference::BtmPlate plate, double ground_z, double c, double f_max)
      : BtmModel(ground_z, c, f_max), plate_(std::move(plate)) {}

 private:
  std::vector<reference::BtmField> spectrum(const std::vector<double>& k, const Vec3& s, const Vec3& l) const override {
    return reference::btmPlateSpectrum(k, plate_, ground_z_, s, l, 2);
  }
  reference::BtmPlate plate_;
};

class BtmBoxModel : public BtmModel {
 public:
  BtmBoxModel(reference::BtmBox box, double ground_z, double c, double f_max) : BtmModel(ground_z, c, f_max), box_(box) {}

 private:
  std::vector<reference::BtmField> spectrum(const std::vector<double>& k, const Vec3& s, const Vec3& l) const override {
    return reference::btmBoxSpectrum(k, box_, ground_z_, s, l, 2);
  }
  reference::BtmBox box_;
};

double triangleArea(const room::Room& room, std::size_t t) {
  const auto& tri = room.mesh.triangles[t];
  const Vec3& a = room.mesh.vertices[static_cast<std::size_t>(tri[0])];
  const Vec3& b = room.mesh.vertices[static_cast<std::size_t>(tri[1])];
  const Vec3& c = room.mesh.vertices[static_cast<std::size_t>(tri[2])];
  return 0.5 * (b - a).cross(c - a).norm();
}

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
  const std::vector<const room::Occluder*> own = room::ownOccluders(room);  // a barrier's side zones are its own
  if (own.size() != 1 || own[0]->type != "barrier") {
    why_not = "the BTM reference fits one barrier";
    return nullptr;
  }
  const room::Occluder& o = *own[0];
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

std::unique_ptr<PointModel> btmBoxModelFor(const room::Room& room, double c, std::string& why_not, std::string& assumption) {
  if (!room.occluders.empty()) {
    why_not = "the BTM box reference fits a scene with no occluders";
    return nullptr;
  }
  const geometry::Mesh& mesh = room.mesh;
  if (mesh.triangles.empty()) {
    why_not = "the scene has no geometry";
    return nullptr;
  }
  double scale = 0.0, floor_z = 1e300;
  for (const Vec3& v : mesh.vertices) {
    scale = std::max(scale, v.cwiseAbs().maxCoeff());
    floor_z = std::min(floor_z, v.z());
  }
  const double tol = 1e-9 * (1.0 + scale);
  const auto vertex = [&](std::size_t t, int i) -> const Vec3& {
    return mesh.vertices[static_cast<std::size_t>(mesh.triangles[t][static_cast<std::size_t>(i)])];
  };
  const auto flat = [&](std::size_t t) {
    for (int i = 0; i < 3; ++i)
      if (std::abs(vertex(t, i).z() - floor_z) > tol) return false;
    return true;
  };
  // The box: the bounds of every triangle not in the lowest horizontal plane.
  Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);
  bool any = false;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (!rigid(room, mesh.object_of_triangle[t])) {
      why_not = "the BTM reference is for rigid surfaces (absorption 0 in every band); " + room.group_of_triangle[t] + " absorbs";
      return nullptr;
    }
    if (flat(t)) continue;
    any = true;
    for (int i = 0; i < 3; ++i) {
      lo = lo.cwiseMin(vertex(t, i));
      hi = hi.cwiseMax(vertex(t, i));
    }
  }
  if (!any || std::abs(lo.z() - floor_z) > tol) {
    why_not = any ? "the BTM box reference fits a box standing on the lowest plane of the scene (the ground or its own bottom)"
                  : "the exact references fit one rigid box or one occluder; every surface of this scene lies in one plane";
    return nullptr;
  }
  // Every other triangle on one of the box's five upper faces (2·axis + side; 4 is the bottom), which they cover.
  double area[6] = {0, 0, 0, 0, 0, 0};
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (flat(t)) continue;
    int face = -1;
    for (int f = 0; f < 6 && face < 0; ++f) {
      const double plane = f % 2 ? hi[f / 2] : lo[f / 2];
      if (std::abs(vertex(t, 0)[f / 2] - plane) <= tol && std::abs(vertex(t, 1)[f / 2] - plane) <= tol &&
          std::abs(vertex(t, 2)[f / 2] - plane) <= tol)
        face = f;
    }
    if (face < 0) {
      why_not = "the BTM box reference fits one axis-aligned box (alone or on a ground); triangle " + std::to_string(t) +
                " (" + room.group_of_triangle[t] + ") is not on a face of the box from " + room::formatNumber(lo.x()) +
                ", " + room::formatNumber(lo.y()) + ", " + room::formatNumber(lo.z()) + " to " +
                room::formatNumber(hi.x()) + ", " + room::formatNumber(hi.y()) + ", " + room::formatNumber(hi.z()) + " m";
      return nullptr;
    }
    area[face] += triangleArea(room, t);
  }
  // The lowest plane: the box's bottom alone (a free box) or a ground reaching beyond it.
  const Vec3 size = hi - lo;
  bool ground = false;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (!flat(t)) continue;
    bool inside = true;
    for (int i = 0; i < 3; ++i)
      for (int a = 0; a < 2; ++a) inside = inside && vertex(t, i)[a] >= lo[a] - tol && vertex(t, i)[a] <= hi[a] + tol;
    if (inside)
      area[4] += triangleArea(room, t);
    else
      ground = true;
  }
  static const char* face_name[6] = {"x-", "x+", "y-", "y+", "bottom", "top"};
  for (int f = 0; f < 6; ++f) {
    if (f == 4 && ground) continue;
    const double want = size[(f / 2 + 1) % 3] * size[(f / 2 + 2) % 3];
    if (std::abs(area[f] - want) > 1e-6 * want) {
      why_not = std::string("the BTM box reference fits a closed box; its ") + face_name[f] + " face is " +
                room::formatNumber(area[f]) + " m² covered of " + room::formatNumber(want) + " m²";
      return nullptr;
    }
  }
  const reference::BtmBox box{lo, hi};
  const auto insideBox = [&](const Vec3& p, double margin) {
    return (p.array() > (lo.array() - margin)).all() && (p.array() < (hi.array() + margin)).all();
  };
  for (const room::Source& s : room.sources)
    if (insideBox(s.position_m, 0.0))
      throw core::InputError(room.file, "source " + s.name + " lies inside or on the box: move it off");
  for (const room::Listener& l : room.listeners) {
    const Vec3 nearest = l.position_m.cwiseMax(lo).cwiseMin(hi);
    if ((nearest - l.position_m).norm() < l.radius_m)
      throw core::InputError(room.file, "listener " + l.name + ": its sphere (radius " + room::formatNumber(l.radius_m) +
                                            " m) meets the box: move it off");
  }
  // The length of the diffracting edges (on a ground, of the box joined with its mirror image).
  const double edges = 4.0 * (size.x() + size.y() + (ground ? 2.0 : 1.0) * size.z());
  const double f_max = kBtmMaxBoxEdgeWavelengths * c / edges;
  char buf[320];
  std::snprintf(buf, sizeof buf,
                "exact: BTM edge diffraction to second order (Svensson et al. 1999) of the rigid %.3g x %.3g x %.3g m box%s, "
                "up to %.0f Hz (its edges%s up to %.0f wavelengths long in all)",
                size.x(), size.y(), size.z(), ground ? " on a rigid ground (image principle)" : " in free field", f_max,
                ground ? ", with their ground mirrors," : "", kBtmMaxBoxEdgeWavelengths);
  assumption = buf;
  return std::make_unique<BtmBoxModel>(box, ground ? floor_z : std::nan(""), c, f_max);
}

}  // namespace diffray::compare
