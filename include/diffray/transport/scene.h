#pragma once
// A signed-energy transport scene: planar occluders carrying WBSDFs, screens (receivers) and plain
// absorbers, built into one Embree scene (or, for tests, a brute-force intersector over the same mesh).
// Every object is a rectangle in its own Frame (world metres). Occluders are indexed by their local x and y:
// a separable WBSDF W(x,y,u,v) = W_x(x,u)·W_y(y,v); a missing y table means the structure
// is uniform along y (an infinitely tall slit or door: a 2D problem). Immutable once built; thread-safe.
#include <memory>
#include <optional>
#include <vector>

#include "diffray/core/error.h"
#include "diffray/geometry/embree_scene.h"
#include "diffray/geometry/frame.h"
#include "diffray/receiver/screen.h"
#include "diffray/receiver/sphere.h"
#include "diffray/wbsdf/table.h"

namespace diffray::transport {

struct Occluder {
  geometry::Frame frame;
  double half_x_m = 1.0, half_y_m = 1.0;
  std::shared_ptr<const wbsdf::WbsdfTable> table_x;  ///< W_x(x, u'): required
  std::shared_ptr<const wbsdf::WbsdfTable> table_y;  ///< W_y(y, v'): null = uniform along y (v' = 0)
  bool reflect = false;  ///< mirror the outgoing direction (paper eq. 9, eq:reflection)
  /// > 0: an ideal thin (spherical) lens of this focal length centred on the frame's origin over the tables'
  /// opening, t = t_x(x)·t_y(y)·exp(−iπ(x² + y²)/(λf)) (paper eq. 11, eq:microstructure). Its WDF is the
  /// opening's sheared, W_t(x, u) = W_x(x, u + x/(λf)) (paper eq. 2: the quadratic phases of t(x ± s/2)
  /// differ by 2πxs/(λf), linear in s), so a ray leaves with the tables' shift plus the geometric deflection
  /// −x/f, −y/f of its direction cosines along ex, ey (scatterAtOccluder). Paraxial, as the phase is; only
  /// separable (rectangular) openings. 0: no lens.
  double focal_length_m = 0;
};

struct Absorber {
  geometry::Frame frame;
  double half_x_m = 1.0, half_y_m = 1.0;
};

/// A collimated (plane-wave) source: rays start uniformly on the window rectangle with direction `dir`.
/// Power = intensity·area·|dir·n| (W when intensity is in W/m²). Monochromatic at wavelength_m, or, when
/// wavelength_max_m > wavelength_m, a flat spectrum in frequency between c/wavelength_max_m and
/// c/wavelength_m: each ray carries one wavelength drawn from it, so fringes average over the band as
/// a band filter would.
struct CollimatedSource {
  geometry::Frame frame;
  double half_x_m = 1.0, half_y_m = 1.0;
  core::Vec3 dir{0, 0, 1};
  double wavelength_m = 0.0;
  double wavelength_max_m = 0.0;  ///< > wavelength_m: a band (see above); otherwise monochromatic
  double intensity = 1.0;
  double power() const;
};

/// A far-field receiver: rays that leave the scene are binned by the direction cosine α = dir·ex over
/// [alpha_lo, alpha_hi) in `bins` bins, whatever their position: the pattern at infinity.
struct FarField {
  core::Vec3 ex{1, 0, 0};
  double alpha_lo = -1.0, alpha_hi = 1.0;
  int bins = 1;
};

enum class ObjectKind { Occluder, Screen, Absorber };

class Scene {
 public:
  int addOccluder(Occluder o);
  int addScreen(receiver::Screen s);
  int addAbsorber(Absorber a);
  /// A transparent listener sphere (not part of the Embree scene: tested analytically per segment).
  int addSphere(receiver::Sphere s);
  /// Bins the escaping rays by direction (one far-field receiver per scene).
  void setFarField(FarField f);
  const FarField* farField() const { return far_field_ ? &*far_field_ : nullptr; }
  /// Builds the Embree scene (brute_force = true: the test back end). Call once after adding objects.
  void build(bool brute_force = false);

  const geometry::Intersector& intersector() const {
    DIFFRAY_CHECK(intersector_ != nullptr);  // build() first
    return *intersector_;
  }
  const geometry::EmbreeScene* embree() const { return dynamic_cast<const geometry::EmbreeScene*>(intersector_.get()); }
  const geometry::Mesh& mesh() const { return mesh_; }

  struct ObjectRef {
    ObjectKind kind;
    int index;  ///< into occluders(), screens() or absorbers()
    geometry::Frame frame;  ///< a copy, so the hot loop reads it without another indirection
    double origin_n, origin_x, origin_y;  ///< origin·n, origin·ex, origin·ey: plane and local offsets
  };
  const ObjectRef& object(int id) const { return objects_[id]; }
  const std::vector<Occluder>& occluders() const { return occluders_; }
  const std::vector<receiver::Screen>& screens() const { return screens_; }
  const std::vector<receiver::Sphere>& spheres() const { return spheres_; }

 private:
  int addObject(ObjectKind kind, int index, const geometry::Frame& f, double hx, double hy);
  std::vector<Occluder> occluders_;
  std::vector<receiver::Screen> screens_;
  std::vector<receiver::Sphere> spheres_;
  std::optional<FarField> far_field_;
  std::vector<Absorber> absorbers_;
  std::vector<ObjectRef> objects_;
  geometry::Mesh mesh_;
  std::unique_ptr<geometry::Intersector> intersector_;
};

}  // namespace diffray::transport
