#include "diffray/transport/room_geometry.h"

#include <cmath>
#include <map>
#include <tuple>

#include "diffray/core/error.h"
#include "diffray/geometry/embree_scene.h"

namespace diffray::transport {

RoomGeometry::RoomGeometry(const room::Room& room, bool brute_force) {
  const geometry::Mesh& mesh = room.mesh;
  if (mesh.triangles.empty()) throw core::InputError(room.file, "the room has no surfaces");
  core::Vec3 lo = mesh.vertices[0], hi = mesh.vertices[0];
  for (const auto& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  extent_ = std::max((hi - lo).maxCoeff(), 1e-3);
  // Coplanar triangles are found by a quantised key (normal to 1e-6, offset to 1e-6 of the extent, sign
  // made canonical). Two coplanar triangles split by a rounding boundary land in two planes: harmless,
  // since an image path is validated against the triangles of its own plane only, never counted twice.
  std::map<std::tuple<long, long, long, long>, int> plane_of_key;
  const double off_q = 1e-6 * extent_;
  triangles_.resize(mesh.triangles.size());
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    const auto& t = mesh.triangles[i];
    const core::Vec3 &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    core::Vec3 n = (b - a).cross(c - a);
    const double len = n.norm();
    TrianglePlane& tp = triangles_[i];
    tp.material = mesh.object_of_triangle[i];
    if (!(len > 0.0)) {  // degenerate: never hit by Embree; keep a harmless plane
      tp.plane = -1;
      continue;
    }
    tp.normal = n / len;
    tp.offset = tp.normal.dot(a);
    core::Vec3 cn = tp.normal;
    double coff = tp.offset;
    const int lead = std::abs(cn.x()) > 0.5 ? 0 : (std::abs(cn.y()) > 0.5 ? 1 : 2);
    if (cn[lead] < 0) {  // every unit vector has a component above 1/√3 > 0.5 in size
      cn = -cn;
      coff = -coff;
    }
    const auto q = [](double v, double step) { return std::lround(v / step); };
    const auto key = std::make_tuple(q(cn.x(), 1e-6), q(cn.y(), 1e-6), q(cn.z(), 1e-6), q(coff, off_q));
    auto [it, inserted] = plane_of_key.emplace(key, static_cast<int>(planes_.size()));
    if (inserted) planes_.push_back({cn, coff, {}});
    planes_[it->second].triangles.push_back(static_cast<int>(i));
    tp.plane = it->second;
  }
  if (brute_force)
    intersector_ = std::make_unique<geometry::BruteForceScene>(mesh);
  else {
    auto scene = std::make_unique<geometry::EmbreeScene>(mesh);
    embree_ = scene->handle();
    intersector_ = std::move(scene);
  }
}

}  // namespace diffray::transport
