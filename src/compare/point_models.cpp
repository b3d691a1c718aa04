#include "diffray/compare/point_models.h"

#include <cmath>

#include <Eigen/Geometry>

#include "diffray/compare/btm_model.h"
#include "diffray/core/error.h"
#include "diffray/reference/aperture_point.h"
#include "diffray/reference/half_plane_point.h"
#include "diffray/room/occluder_file.h"
#include "diffray/transport/room_geometry.h"
#include "diffray/utd/paths.h"

namespace diffray::compare {

using core::Vec3;
using Kind = room::OccluderAxis::Kind;

namespace {

// The half-plane reference in the frame of an edge occluder: edge through E0 along ey, screen toward −ex.
// 1/p_free = R·e^{ikR} at frequency f, distance r (time factor e^{iωt}).
std::complex<double> unfree(double f_hz, double r_m, double c_m_s) {
  return std::polar(r_m, 2.0 * 3.14159265358979323846 * f_hz * r_m / c_m_s);
}

class HalfPlaneModel : public PointModel {
 public:
  HalfPlaneModel(const room::Occluder& o, double c, bool rigid)
      : e0_(o.origin_m - o.half_x_m * o.ex), x_(-o.ex), y_(o.normal), z_(o.ey), c_(c), rigid_(rigid) {}
  std::string name() const override { return "exact"; }
  std::vector<std::complex<double>> relativePressure(const Vec3& s, const Vec3& l, const std::vector<double>& f) const override {
    const reference::CylindricalPoint ps = toFrame(s), pl = toFrame(l);
    const double r = (l - s).norm();
    std::vector<std::complex<double>> out;
    for (double fj : f) out.push_back(reference::halfPlanePointSource(c_ / fj, ps, pl, rigid_) * unfree(fj, r, c_));
    return out;
  }

 private:
  reference::CylindricalPoint toFrame(const Vec3& p) const {
    const Vec3 d = p - e0_;
    return reference::halfPlaneFrameFromCartesian(d.dot(x_), d.dot(y_), d.dot(z_));
  }
  Vec3 e0_, x_, y_, z_;
  double c_;
  bool rigid_;
};

// The Rayleigh–Sommerfeld reference in the frame of an opening occluder: screen z = 0, the source at z < 0.
// With a floor and `incoherent`, the direct and the floor-reflected arrivals add as energies, as they do in
// an energy ray tracer: |U(P)|² + |U(P')|² with U the field of the source through the opening unfolded
// about the floor (the opening and its mirror image) and P' the listener's mirror image.
class ApertureModel : public PointModel {
 public:
  ApertureModel(const room::Occluder& o, double c, bool incoherent) : o_(o), c_(c), incoherent_(incoherent) {
    if (incoherent_ && o.y.mirror_lo) {
      screen_.openings.push_back({-o.half_x_m, o.half_x_m, -3.0 * o.half_y_m, o.half_y_m});
      floor_ = -o.half_y_m;
    } else {
      screen_.openings.push_back({-o.half_x_m, o.half_x_m, -o.half_y_m, o.half_y_m});
      if (o.y.mirror_lo) screen_.floor_y_m = -o.half_y_m;
    }
  }
  std::string name() const override { return incoherent_ ? "exact-incoherent-floor" : "exact"; }
  bool addsEnergies() const override { return floor_.has_value(); }
  std::vector<double> relativeEnergy(const Vec3& s, const Vec3& l, const std::vector<double>& f) const override {
    const double r = (l - s).norm();
    const reference::CartesianPoint ps = frame(s, s), pl = frame(s, l);
    reference::CartesianPoint mirror = pl;
    if (floor_) mirror.y_m = 2.0 * *floor_ - pl.y_m;
    std::vector<double> out;
    for (double fj : f) {
      double e = std::norm(reference::aperturePointSource(c_ / fj, screen_, ps, pl) * r);
      if (floor_) e += std::norm(reference::aperturePointSource(c_ / fj, screen_, ps, mirror) * r);
      out.push_back(e);
    }
    return out;
  }
  std::vector<std::complex<double>> relativePressure(const Vec3& s, const Vec3& l, const std::vector<double>& f) const override {
    if (floor_) return std::vector<std::complex<double>>(f.size(), {std::nan(""), std::nan("")});  // energies added
    const double r = (l - s).norm();
    const reference::CartesianPoint ps = frame(s, s), pl = frame(s, l);
    std::vector<std::complex<double>> out;
    for (double fj : f) out.push_back(reference::aperturePointSource(c_ / fj, screen_, ps, pl) * unfree(fj, r, c_));
    return out;
  }

 private:
  // p in the screen frame, its z axis turned so that the source s lies at z < 0.
  reference::CartesianPoint frame(const Vec3& s, const Vec3& p) const {
    const double side = (s - o_.origin_m).dot(o_.normal) < 0.0 ? 1.0 : -1.0;
    const Vec3 d = p - o_.origin_m;
    return reference::CartesianPoint{d.dot(o_.ex), d.dot(o_.ey), side * d.dot(o_.normal)};
  }

  room::Occluder o_;
  reference::ApertureScreen screen_;
  double c_;
  bool incoherent_;
  std::optional<double> floor_;  ///< incoherent mode: the floor's y in the screen frame
};

class UtdPointModel : public PointModel {
 public:
  UtdPointModel(const room::Room& room, double c) : room_(room), geometry_(room), c_(c) {
    utd::UtdOptions opt;
    opt.material_reflection = true;
    opt.second_order_reflections = 3;  // free-field scenes have few planes: every combination is cheap
    model_ = std::make_unique<utd::UtdModel>(room_, geometry_, opt);
  }
  std::string name() const override { return "utd"; }
  std::vector<std::complex<double>> relativePressure(const Vec3& s, const Vec3& l, const std::vector<double>& f) const override {
    const double r = (l - s).norm();
    const std::vector<utd::Path> paths = model_->paths(s, l);
    std::vector<std::complex<double>> out;
    for (double fj : f) out.push_back(model_->total(paths, fj, c_) * unfree(fj, r, c_));
    return out;
  }

 private:
  room::Room room_;
  transport::RoomGeometry geometry_;
  double c_;
  std::unique_ptr<utd::UtdModel> model_;
};

}  // namespace

std::unique_ptr<PointModel> exactModelFor(const room::Room& room, double c, std::string& why_not,
                                          std::string& assumption, bool incoherent_floor) {
  if (room.occluders.empty()) return btmBoxModelFor(room, c, why_not, assumption);
  const std::vector<const room::Occluder*> own = room::ownOccluders(room);
  if (own.size() != 1) {
    why_not = "the exact references fit a scene with exactly one occluder (an edge/barrier or a door/slit); this one has " +
              std::to_string(own.size());
    return nullptr;
  }
  std::string btm_why_not;
  if (auto btm = btmModelFor(room, c, btm_why_not, assumption)) return btm;
  if (own.size() != room.occluders.size()) {  // side edges: no infinite half-plane stands for them
    why_not = btm_why_not + " (barrier " + own[0]->name + " diffracts at its side edges too)";
    return nullptr;
  }
  const room::Occluder& o = *own[0];
  if (o.x.kind == Kind::Edge && o.y.kind == Kind::Uniform) {
    assumption = "exact: Macdonald's point source on an infinite thin " +
                 std::string(o.x.faces == room::OccluderAxis::Faces::Soft ? "soft" : "rigid") + " half-plane along the edge of occluder " + o.name;
    return std::make_unique<HalfPlaneModel>(o, c, o.x.faces != room::OccluderAxis::Faces::Soft);
  }
  if (o.x.kind == Kind::Opening && o.y.kind == Kind::Opening && !o.x.mirror_lo) {
    assumption = "exact: Rayleigh–Sommerfeld over the opening of " + o.name + " in an infinite black screen" +
                 (o.y.mirror_lo ? (incoherent_floor ? " on a rigid floor, floor reflection added as energy"
                                                    : " on a rigid floor")
                                : "");
    return std::make_unique<ApertureModel>(o, c, incoherent_floor);
  }
  why_not = "no exact reference for occluder " + o.name + " (type " + o.type + "): references exist for one edge/barrier or one door/slit";
  return nullptr;
}

std::unique_ptr<PointModel> utdModelFor(const room::Room& room, double c) {
  return std::make_unique<UtdPointModel>(room, c);
}

std::vector<double> bandRelativeEnergies(const PointModel& m, const Vec3& source, const Vec3& listener, double radius_m,
                                         const std::vector<std::pair<double, double>>& bands_hz, int points) {
  if (points < 1) throw core::InternalError("bandRelativeEnergies: bad band");
  std::vector<double> f;
  for (const auto& [lo_hz, hi_hz] : bands_hz) {
    if (!(hi_hz >= lo_hz) || !(lo_hz > 0.0)) throw core::InternalError("bandRelativeEnergies: bad band");
    for (int j = 0; j < points; ++j) f.push_back(lo_hz + (j + 0.5) * (hi_hz - lo_hz) / points);
  }
  // Degree-3 ball rule: the six points ±a·e_i, a = R·√(3/5), equal weights (⟨x²⟩ = R²/5 over the ball).
  const double a = radius_m * std::sqrt(0.6);
  const double r_centre2 = (listener - source).squaredNorm();
  std::vector<double> sum(bands_hz.size(), 0.0);
  // The rule's axes are turned by a fixed rotation so that no point lies exactly on a shadow boundary
  // through the centre (a plane that often contains a coordinate axis), where a point model's geometric
  // visibility is decided by float rounding; the rule is exact for cubics in any orientation.
  static const Eigen::Matrix3d turn = (Eigen::AngleAxisd(0.7, Vec3(0, 0, 1)) * Eigen::AngleAxisd(0.5, Vec3(0, 1, 0)) *
                                       Eigen::AngleAxisd(0.3, Vec3(1, 0, 0))).toRotationMatrix();
  for (int k = 0; k < 6; ++k) {
    const Vec3 q = listener + (k % 2 ? a : -a) * turn.col(k / 2);
    // relativeEnergy is |p·R_q|²; re the free field at the centre it is |p|²·R_c² = that·R_c²/R_q².
    const double to_centre = r_centre2 / (q - source).squaredNorm();
    const std::vector<double> e = m.relativeEnergy(source, q, f);  // every band's frequencies in one call
    for (std::size_t j = 0; j < f.size(); ++j) sum[j / static_cast<std::size_t>(points)] += e[j] * to_centre;
  }
  for (double& v : sum) v /= 6.0 * points;
  return sum;
}

double bandRelativeEnergy(const PointModel& m, const Vec3& source, const Vec3& listener, double radius_m,
                          double lo_hz, double hi_hz, int points) {
  return bandRelativeEnergies(m, source, listener, radius_m, {{lo_hz, hi_hz}}, points)[0];
}

std::vector<double> PointModel::relativeEnergy(const Vec3& source, const Vec3& listener,
                                               const std::vector<double>& freqs_hz) const {
  std::vector<double> out;
  for (const std::complex<double>& p : relativePressure(source, listener, freqs_hz)) out.push_back(std::norm(p));
  return out;
}

}  // namespace diffray::compare
