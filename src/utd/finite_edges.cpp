// The finite-edge factor of the UTD model's first-order diffractions (utd/paths.h, "Finite edges"): the
// stationary-phase integral of the BTM edge-source integral between the edge's ends (Svensson, Fred &
// Vanderkooy 1999; a stationary point near an end point: Felsen & Marcuvitz 1973, §4.2), and which ends are
// not ends (a foot standing on a face perpendicular to the edge, whose mirror image continues it).
#include <cmath>
#include <limits>
#include <utility>

#include "diffray/room/air.h"
#include "diffray/utd/coefficient.h"
#include "path_util.h"

namespace diffray::utd {

using core::Vec3;
using cd = std::complex<double>;

namespace {

// ∫_u^∞ e^{−iτ²} dτ for any real u, from the transition function: F(X) = 2i√X e^{iX} ∫_{√X}^∞ e^{−iτ²} dτ
// (coefficient.h), and the whole line's integral √π e^{−iπ/4}.
cd tail(double u) {
  const cd whole = std::sqrt(core::kPi) * std::polar(1.0, -0.25 * core::kPi);
  if (u == 0.0) return 0.5 * whole;
  if (std::isinf(u)) return u > 0.0 ? cd(0.0) : whole;
  const double a = std::abs(u);
  const cd right = transitionF(a * a) * std::exp(cd(0.0, -a * a)) / cd(0.0, 2.0 * a);
  return u > 0.0 ? right : whole - right;
}

}  // namespace

void UtdModel::findEdgeRanges() {
  const double inf = std::numeric_limits<double>::infinity();
  const auto& planes = geometry_.planes();
  // An end stands on a face when a plane perpendicular to the edge holds it and, beside it on the edge's air
  // side, one of the plane's triangles: the face the air sees continue under the edge's mirror image.
  const auto standsOn = [&](const Edge& e, const Vec3& end) {
    const Vec3 beside = end + 100.0 * offsetAt(end) * e.bisector();
    for (std::size_t k = 0; k < planes.size(); ++k) {
      if (std::abs(planes[k].normal.dot(e.tangent)) < 1.0 - 1e-9) continue;
      if (std::abs(detail::signedDistance(planes[k], end)) > offsetAt(end)) continue;
      if (triangleAt(static_cast<int>(k), beside) >= 0) return true;
    }
    return false;
  };
  range_.clear();
  for (const Edge& e : edges_) {
    const bool at_start = standsOn(e, e.start), at_end = standsOn(e, e.end);
    if (at_start && at_end)
      range_.push_back({-inf, inf});
    else
      range_.push_back({at_start ? -e.length_m : 0.0, at_end ? 2.0 * e.length_m : e.length_m});
  }
}

std::complex<double> UtdModel::truncation(const Diffraction& d, double k) const {
  if (!options_.finite_edges || !(d.curvature > 0.0)) return 1.0;
  const auto& [lo, hi] = range_[d.edge];
  const double scale = std::sqrt(0.5 * k * d.curvature);
  const cd whole = std::sqrt(core::kPi) * std::polar(1.0, -0.25 * core::kPi);
  return (tail((lo - d.arc_m) * scale) - tail((hi - d.arc_m) * scale)) / whole;
}

bool UtdModel::keepsCorner(int e, double arc, double curvature) const {
  // Only beyond a free end: beyond a foot the stationary point lies on the edge's mirror image, whose
  // paths are the ones with the reflection off that face.
  const double length = edges_[e].length_m;
  const auto& [lo, hi] = range_[e];
  double beyond = 0.0;
  if (arc < 0.0 && lo == 0.0) beyond = -arc;
  if (arc > length && hi == length) beyond = arc - length;
  const double k_low = core::kTwoPi * room_.bands.lowerHz(0) / room::speedOfSound(room_.air);
  return beyond > 0.0 && beyond * std::sqrt(0.5 * k_low * curvature) <= 3.0;
}

}  // namespace diffray::utd
