#pragma once
// A pinhole camera whose pixels are finite apertures (paper section 2.4: negative WBSDF energy is
// physical only once integrated over an aperture). Frame: world metres. forward f = normalize(look_at −
// position), right r = normalize(f × up), image up u = r × f. A world point p with q = p − position and
// depth z = q·f > 0 lands on the image plane at distance 1 at (X, Y) = (q·r/z, q·u/z); the plane spans
// |X| ≤ tan(fov_x/2), |Y| ≤ tan(fov_x/2)·height/width (square pixels). Pixel (ix, iy), iy = 0 the top row,
// covers X ∈ [−T + ix·s, −T + (ix+1)·s], Y ∈ [T_y − (iy+1)·s, T_y − iy·s], s = 2T/width.
// A pixel's value is the mean radiance over its solid angle (pixelSolidAngle(), exact for the rectangle on
// the image plane). Immutable; thread-safe.
#include "diffray/core/math.h"

namespace diffray::render {

using core::Vec3;

struct CameraSpec {
  Vec3 position_m{0, 0, 0};
  Vec3 look_at_m{0, 0, 1};
  Vec3 up{0, 1, 0};
  double fov_x_deg = 40.0;  ///< horizontal field of view, (0, 170]
  int width = 320, height = 240;
};

class Camera {
 public:
  /// Throws core::InputError (field "camera.…") for a zero view direction, an up parallel to it, a field of
  /// view outside (0, 170] degrees or a size outside 1…16384 pixels.
  explicit Camera(const CameraSpec& spec);

  struct Projection {
    int ix = -1, iy = -1;  ///< the pixel, or −1 when the point lies outside the image or behind the camera
    double distance_m = 0.0;  ///< |p − position|
    Vec3 to_camera{0, 0, 0};  ///< unit vector from p to the pinhole
    bool inside() const { return ix >= 0; }
  };
  Projection project(const Vec3& p) const;

  /// Solid angle (sr) the pixel subtends at the pinhole: Σ ± atan(XY/√(1 + X² + Y²)) over its corners.
  double pixelSolidAngle(int ix, int iy) const;
  /// Unit direction from the pinhole through image-plane point (X, Y).
  Vec3 direction(double X, double Y) const { return (forward_ + X * right_ + Y * up_).normalized(); }

  const CameraSpec& spec() const { return spec_; }
  int width() const { return spec_.width; }
  int height() const { return spec_.height; }
  const Vec3& position() const { return spec_.position_m; }
  const Vec3& forward() const { return forward_; }
  const Vec3& right() const { return right_; }
  const Vec3& imageUp() const { return up_; }
  double halfWidthTan() const { return tan_x_; }
  double halfHeightTan() const { return tan_y_; }
  double pixelPitch() const { return pitch_; }  ///< s: a pixel's side on the image plane at distance 1

 private:
  CameraSpec spec_;
  Vec3 forward_, right_, up_;
  double tan_x_ = 0, tan_y_ = 0, pitch_ = 0;
};

}  // namespace diffray::render
