#include "diffray/transport/room_occluders.h"

#include <algorithm>
#include <cmath>

#include "diffray/core/error.h"
#include "diffray/room/air.h"
#include "diffray/wbsdf/edge_kernel.h"
#include "diffray/wbsdf/microstructure.h"

namespace diffray::transport {

using core::Vec3;
using Kind = room::OccluderAxis::Kind;

namespace {

// Smallest edge distance used for the kernel (m): a hit within float rounding of an edge.
constexpr double kMinEdgeDistanceM = 1e-9;

std::shared_ptr<const wbsdf::WbsdfTable> tableFor(const room::OccluderAxis& a, double lambda_m) {
  wbsdf::TableOptions opt;
  opt.wavelength_m = lambda_m;
  opt.coarsen_to_fit = true;
  if (a.kind == Kind::Slits)
    return wbsdf::WbsdfTable::build(*wbsdf::Openings::slits(a.count, a.hi_m - a.lo_m, a.spacing_m), opt);
  if (a.kind == Kind::Grating) return wbsdf::WbsdfTable::build(wbsdf::PhaseGrating(a.period_m, a.modulation_m), opt);
  return nullptr;
}

}  // namespace

// The energy factor |1 ± c1/c2|² of OccluderAxis::Faces for a ray arriving along d_in and leaving along
// d_out across an edge whose open side lies along `open` (unit, in the occluder's plane, perpendicular to the
// edge) with occluder normal `n`. Angles in the plane across the edge, from the screen face (direction
// −open) toward the side the ray comes from: φ0 of the direction back to the source, φ of the outgoing
// direction, in [0, 2π). Capped at 4, the grazing limit (incident and reflected waves coincide).
double facesFactor(room::OccluderAxis::Faces faces, const Vec3& open, const Vec3& n, const Vec3& d_in,
                   const Vec3& d_out) {
  if (faces == room::OccluderAxis::Faces::Kirchhoff) return 1.0;
  const double side = -d_in.dot(n) >= 0.0 ? 1.0 : -1.0;  // the source's side of the plane is +Y
  const double x0 = -(-d_in).dot(open), y0 = side * (-d_in).dot(n);
  const double x1 = -d_out.dot(open), y1 = side * d_out.dot(n);
  if (x0 * x0 + y0 * y0 < 1e-24 || x1 * x1 + y1 * y1 < 1e-24) return 1.0;  // along the edge: no plane
  const double phi0 = std::atan2(y0, x0);
  double phi = std::atan2(y1, x1);
  if (phi < 0.0) phi += core::kTwoPi;
  const double c1 = std::cos(0.5 * (phi - phi0)), c2 = std::cos(0.5 * (phi + phi0));
  if (std::abs(c2) < 1e-12) return 4.0;
  const double a = faces == room::OccluderAxis::Faces::Rigid ? 1.0 + c1 / c2 : 1.0 - c1 / c2;
  return std::min(4.0, a * a);
}

RoomOccluders::RoomOccluders(const room::Room& room, double shortest_wavelength_m) {
  core::requirePositive("shortest wavelength", shortest_wavelength_m);
  of_triangle_.assign(room.mesh.triangleCount(), -1);
  mask_.assign(room.mesh.triangleCount(), 0);
  for (const room::Occluder& o : room.occluders) {
    const int k = static_cast<int>(occluders_.size());
    Entry e;
    e.spec = o;
    e.x = {o.x, tableFor(o.x, shortest_wavelength_m)};
    e.y = {o.y, tableFor(o.y, shortest_wavelength_m)};
    occluders_.push_back(std::move(e));
    int found = 0;
    for (std::size_t t = 0; t < room.group_of_triangle.size(); ++t)
      if (room.group_of_triangle[t] == o.group) {
        of_triangle_[t] = k;
        mask_[t] = 1;
        ++found;
      }
    if (found == 0) throw core::InternalError("occluder " + o.name + " has no triangles (group " + o.group + ")");
  }
  // Once every occluder's triangles are known (a surround is never another occluder's opening).
  const double c = room::speedOfSound(room.air);
  for (Entry& e : occluders_) {
    e.surround = surroundReflectance(room, e.spec, of_triangle_);
    for (int b = 0; b < room.bands.size(); ++b) e.returns = e.returns || e.surround[b] > 0.0;
    if (!e.returns) continue;
    auto length = [](const room::OccluderAxis& a) {
      return a.kind == Kind::Opening ? (a.mirror_lo ? 2.0 : 1.0) * (a.hi_m - a.lo_m) : 0.0;
    };
    e.tau = OpeningTransmission(length(e.spec.x), length(e.spec.y), room.bands, c);
  }
}

void RoomOccluders::edgeDistance(const Axis& a, double c, double& four_d, double& open_sign) {
  double d = a.spec.hi_m - c;
  open_sign = -1.0;  // the hi edge: its open side lies toward −axis
  if (a.spec.kind == Kind::Edge || (!a.spec.mirror_lo && c - a.spec.lo_m < d)) {
    d = c - a.spec.lo_m;
    open_sign = 1.0;
  }
  four_d = 4.0 * std::max(d, kMinEdgeDistanceM);
}

void RoomOccluders::sampleAxis(const Axis& a, double c, double lambda_m, double alpha, double alpha_max,
                               const double* xi, double& u, double& w, double& open_sign) {
  open_sign = 0.0;
  switch (a.spec.kind) {
    case Kind::Uniform:
      u = 0.0, w = 1.0;
      return;
    case Kind::Opening:
    case Kind::Edge: {
      // W = 4d·sinc(4du), d the distance to the nearer diffracting edge (wbsdf/edge_kernel.h); u' = w/(4d),
      // drawn only where the outgoing cosine α + λu' stays within ±alpha_max (the rest is evanescent).
      double four_d;
      edgeDistance(a, c, four_d, open_sign);
      const double d = 0.25 * four_d;
      const double scale = 4.0 * d / lambda_m;  // w per unit of direction cosine
      const wbsdf::EdgeKernelSample s =
          wbsdf::edgeKernelSample(std::min(0.0, (-alpha_max - alpha) * scale), std::max(0.0, (alpha_max - alpha) * scale),
                                  xi[0], xi[1]);
      u = s.w / (4.0 * d), w = s.weight;
      return;
    }
    case Kind::Slits:
    case Kind::Grating: {
      const wbsdf::WbsdfTable::Sample s = a.table->sample(c, xi[0]);
      u = s.u_shift, w = s.weight;
      return;
    }
  }
  u = 0.0, w = 0.0;
}

RoomOccluders::Scatter RoomOccluders::scatter(int k, const Vec3& p, const Vec3& dir, double lambda_m,
                                              const double xi[4]) const {
  const Entry& e = occluders_[k];
  const room::Occluder& o = e.spec;
  const Vec3 local = p - o.origin_m;
  const double x = local.dot(o.ex), y = local.dot(o.ey);
  Scatter s;
  // Paper eq. 8 (angle-shift invariance): direction cosines along ex, ey shift by λu', λv'. Only propagating
  // outcomes α'² + β'² < 1 are drawn: the x shift first, within |α'| < √(1 − β²) when nothing diffracts
  // along y (β' = β) and |α'| < 1 otherwise, then the y shift within |β'| < √(1 − α'²).
  const double alpha_i = dir.dot(o.ex), beta_i = dir.dot(o.ey);
  const double alpha_max = e.y.spec.kind == Kind::Uniform ? std::sqrt(std::max(0.0, 1.0 - beta_i * beta_i)) : 1.0;
  double u, wx, v, wy, open_x, open_y;
  sampleAxis(e.x, x, lambda_m, alpha_i, alpha_max, xi, u, wx, open_x);
  const double alpha = alpha_i + lambda_m * u;
  sampleAxis(e.y, y, lambda_m, beta_i, std::sqrt(std::max(0.0, 1.0 - alpha * alpha)), xi + 2, v, wy, open_y);
  s.weight = wx * wy;
  if (s.weight == 0.0) return s;
  const double beta = beta_i + lambda_m * v;
  const double gamma_sq = 1.0 - alpha * alpha - beta * beta;
  if (gamma_sq <= 0.0) {
    s.evanescent = true;
    return s;
  }
  double gamma = std::copysign(std::sqrt(gamma_sq), dir.dot(o.normal));
  if (o.reflect) gamma = -gamma;  // paper eq. 9: the mirrored outgoing wave
  s.dir = alpha * o.ex + beta * o.ey + gamma * o.normal;
  if (open_x != 0.0) s.weight *= facesFactor(e.x.spec.faces, open_x * o.ex, o.normal, dir, s.dir);
  if (open_y != 0.0) s.weight *= facesFactor(e.y.spec.faces, open_y * o.ey, o.normal, dir, s.dir);
  s.alive = true;
  return s;
}

}  // namespace diffray::transport
