#include "diffray/render/camera.h"

#include <cmath>

#include "diffray/core/error.h"

namespace diffray::render {

Camera::Camera(const CameraSpec& spec) : spec_(spec) {
  const Vec3 view = spec.look_at_m - spec.position_m;
  if (!(view.norm() > 0)) throw core::InputError("camera.look_at", "must differ from camera.position");
  forward_ = view.normalized();
  const Vec3 r = forward_.cross(spec.up);
  if (!(r.norm() > 1e-9 * spec.up.norm()) || !(spec.up.norm() > 0))
    throw core::InputError("camera.up", "must be non-zero and not parallel to the view direction");
  right_ = r.normalized();
  up_ = right_.cross(forward_);
  if (!(spec.fov_x_deg > 0 && spec.fov_x_deg <= 170))
    throw core::InputError("camera.fov_deg", "must be in (0, 170] degrees");
  if (spec.width < 1 || spec.width > 16384 || spec.height < 1 || spec.height > 16384)
    throw core::InputError("camera.pixels", "width and height must be in 1…16384");
  tan_x_ = std::tan(0.5 * spec.fov_x_deg * core::kPi / 180.0);
  pitch_ = 2.0 * tan_x_ / spec.width;
  tan_y_ = 0.5 * pitch_ * spec.height;
}

Camera::Projection Camera::project(const Vec3& p) const {
  Projection out;
  const Vec3 q = p - spec_.position_m;
  const double z = q.dot(forward_);
  if (!(z > 0)) return out;
  const double X = q.dot(right_) / z, Y = q.dot(up_) / z;
  const double fx = (X + tan_x_) / pitch_, fy = (tan_y_ - Y) / pitch_;
  if (!(fx >= 0 && fx < spec_.width && fy >= 0 && fy < spec_.height)) return out;
  out.ix = static_cast<int>(fx);
  out.iy = static_cast<int>(fy);
  out.distance_m = q.norm();
  out.to_camera = -q / out.distance_m;
  return out;
}

double Camera::pixelSolidAngle(int ix, int iy) const {
  // Solid angle of the image-plane rectangle [x0, x1] × [y0, y1] at distance 1 from the pinhole:
  // F(x1,y1) − F(x0,y1) − F(x1,y0) + F(x0,y0) with F(x, y) = atan(xy/√(1 + x² + y²)).
  const double x0 = -tan_x_ + ix * pitch_, x1 = x0 + pitch_;
  const double y1 = tan_y_ - iy * pitch_, y0 = y1 - pitch_;
  auto F = [](double x, double y) { return std::atan(x * y / std::sqrt(1.0 + x * x + y * y)); };
  return F(x1, y1) - F(x0, y1) - F(x1, y0) + F(x0, y0);
}

}  // namespace diffray::render
