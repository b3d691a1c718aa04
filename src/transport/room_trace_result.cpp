// RoomTraceResult's merge and the tracer's sizing and emission functions (declared in room_tracer.h), apart
// from the bounce loop in room_tracer.cpp.
#include <algorithm>
#include <cmath>
#include <sstream>

#include "diffray/core/error.h"
#include "diffray/core/math.h"
#include "diffray/transport/room_tracer.h"

namespace diffray::transport {

void RoomTraceResult::merge(const RoomTraceResult& o) {
  if (listeners.empty()) {
    listeners = o.listeners;
    crossings = o.crossings;
    in_flight = o.in_flight;
    directions = o.directions;
  } else {
    for (std::size_t i = 0; i < listeners.size(); ++i) {
      listeners[i].merge(o.listeners[i]);
      crossings[i] += o.crossings[i];
    }
    for (std::size_t i = 0; i < directions.size() && i < o.directions.size(); ++i) directions[i].merge(o.directions[i]);
    if (in_flight.bins() > 0) in_flight.merge(o.in_flight);
  }
  rays += o.rays;
  segments += o.segments;
  escaped += o.escaped;
  roulette_killed += o.roulette_killed;
  timed_out += o.timed_out;
  occluder_events += o.occluder_events;
  evanescent += o.evanescent;
}

int histogramBins(double length_s, double bin_s, int bands, std::size_t listeners, bool directions) {
  core::requirePositive("length", length_s);
  core::requirePositive("histogram bin", bin_s);
  const double bins = std::max(1.0, std::ceil(length_s / bin_s));
  const double cells =
      bins * bands * static_cast<double>(std::max<std::size_t>(listeners, 1)) * (directions ? 7.0 / 4.0 : 1.0);
  if (!(cells <= kMaxHistogramCells)) {
    std::ostringstream why;
    why.precision(3);
    why << "an IR of " << length_s << " s in bins of " << bin_s << " s for " << bands << " bands and " << listeners
        << " listener(s) needs " << cells << " histogram cells" << (directions ? " (with the direction tallies)" : "")
        << ", more than the limit of " << kMaxHistogramCells
        << "; use wider bins or a shorter IR (ir_length_s, max_length_s, --length)";
    throw core::InputError("output.histogram_bin_s", why.str());
  }
  return static_cast<int>(bins);
}

double directivityGain(const room::Directivity& d, double cos_theta) {
  const double amp = d.a + (1.0 - d.a) * cos_theta;
  return amp * amp / (d.a * d.a + (1.0 - d.a) * (1.0 - d.a) / 3.0);
}

namespace {

// One rectangle of an aimed emission (its `also` list aside), with its mirror image if `mirrored`.
core::Vec3 towardRectangle(const EmissionTarget& t, const core::Vec3& source, double xi1, double xi2, double& scale) {
  const bool image = t.mirrored && xi2 >= 0.5;
  if (t.mirrored) xi2 = image ? 2.0 * xi2 - 1.0 : 2.0 * xi2;
  // d: distance from the −x side; uniform, or with probability edge_fraction log-uniform in d + d0.
  const double width = 2.0 * t.half_x_m, d0 = t.edge_scale_m, f = t.edge_fraction;
  const double log_span = std::log((width + d0) / d0);
  double d;
  if (xi1 < f) d = std::min(width, d0 * std::exp(xi1 / f * log_span) - d0);
  else d = (xi1 - f) / (1.0 - f) * width;
  const double pdf_x = (1.0 - f) / width + (f > 0.0 ? f / ((d + d0) * log_span) : 0.0);
  core::Vec3 q = t.origin + (d - t.half_x_m) * t.ex + (2.0 * xi2 - 1.0) * t.half_y_m * t.ey;
  if (image) q -= 2.0 * (t.mirror_normal.dot(q) - t.mirror_offset) * t.mirror_normal;
  const core::Vec3 to = q - source;
  const double dist2 = to.squaredNorm();
  const core::Vec3 dir = to / std::sqrt(dist2);
  const double cos_t = std::abs(dir.dot(t.ex.cross(t.ey)));
  // 1/(4π·pdf per steradian), pdf = pdf_x·pdf_y·r²/cosθ with pdf_y = 1/(2·half_y).
  scale = cos_t * 2.0 * t.half_y_m / (pdf_x * 4.0 * core::kPi * dist2);
  if (t.mirrored) scale *= 2.0;  // each of the rectangle and its image takes half the rays
  return dir;
}

}  // namespace

core::Vec3 emissionDirection(const EmissionTarget* aim, const core::Vec3& source, double xi1, double xi2,
                             double& scale) {
  scale = 1.0;
  if (!aim) {
    const double z = 1.0 - 2.0 * xi1, phi = core::kTwoPi * xi2;
    const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
    return core::Vec3(r * std::cos(phi), r * std::sin(phi), z);
  }
  if (aim->also.empty()) return towardRectangle(*aim, source, xi1, xi2, scale);
  // Several rectangles: an equal share of the rays each, xi2's slot picking one (then rescaled within it).
  const std::size_t count = 1 + aim->also.size();
  const double x = xi2 * static_cast<double>(count);
  const std::size_t k = std::min(count - 1, static_cast<std::size_t>(x));
  const core::Vec3 dir = towardRectangle(k == 0 ? *aim : aim->also[k - 1], source, xi1,
                                         std::min(1.0, x - static_cast<double>(k)), scale);
  scale *= static_cast<double>(count);
  return dir;
}

}  // namespace diffray::transport
