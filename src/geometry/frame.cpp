#include "diffray/geometry/frame.h"

#include "diffray/core/error.h"

namespace diffray::geometry {

Frame Frame::make(const core::Vec3& origin, const core::Vec3& normal, const core::Vec3& x_hint) {
  Frame f;
  f.origin = origin;
  if (!(normal.norm() > 0)) throw core::InputError("normal", "must be a non-zero vector");
  f.n = normal.normalized();
  core::Vec3 x = x_hint - x_hint.dot(f.n) * f.n;
  if (x.norm() < 1e-9) x = (std::abs(f.n.x()) < 0.9 ? core::Vec3(1, 0, 0) : core::Vec3(0, 1, 0)) -
                           f.n * (std::abs(f.n.x()) < 0.9 ? f.n.x() : f.n.y());
  f.ex = x.normalized();
  f.ey = f.n.cross(f.ex);
  return f;
}

}  // namespace diffray::geometry
