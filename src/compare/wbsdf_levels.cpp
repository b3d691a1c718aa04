#include "diffray/compare/wbsdf_levels.h"

#include <cmath>
#include <limits>

#include "diffray/core/error.h"
#include "diffray/room/air.h"
#include "diffray/transport/room_geometry.h"
#include "diffray/transport/room_occluders.h"
#include "diffray/transport/room_tracer.h"

namespace diffray::compare {

double levelDb(double ratio) {
  if (std::isnan(ratio)) return ratio;  // no value (a reference above its size limit)
  return ratio > 0.0 ? 10.0 * std::log10(ratio) : -std::numeric_limits<double>::infinity();
}

void aimAtOccluder(WbsdfRunOptions& w, const room::Occluder& o) {
  const bool doubled = o.y.kind == room::OccluderAxis::Kind::Opening && o.y.mirror_lo;
  w.aim = true;
  w.aim_origin = doubled ? o.origin_m - o.half_y_m * o.ey : o.origin_m;
  w.aim_ex = o.ex;
  w.aim_ey = o.ey;
  w.aim_half_x_m = o.half_x_m;
  w.aim_half_y_m = doubled ? 2.0 * o.half_y_m : o.half_y_m;
}

WbsdfLevels wbsdfLevels(const room::Room& room, int source, const WbsdfRunOptions& options) {
  if (source < 0 || source >= static_cast<int>(room.sources.size())) throw core::InternalError("wbsdfLevels: no such source");
  const transport::RoomGeometry geometry(room);
  const double c = room::speedOfSound(room.air);
  const transport::RoomOccluders occluders(room, c / room.bands.upperHz(room.bands.size() - 1));
  transport::RoomTraceOptions opt;
  opt.rays = options.rays;
  opt.seed = options.seed;
  opt.length_s = options.length_s;
  opt.bin_s = options.length_s;  // one bin: the whole arrival's energy, with its standard error
  opt.skip_order = -1;           // no image sources here: the rays carry every path
  opt.speed_of_sound_m_s = c;
  opt.on_progress = options.on_progress;
  opt.next_event = options.next_event;
  if (options.diffraction && !occluders.empty()) opt.occluders = &occluders;
  transport::EmissionTarget aim{options.aim_origin, options.aim_ex, options.aim_ey, options.aim_half_x_m,
                                options.aim_half_y_m, options.aim_edge_fraction, options.aim_edge_scale_m,
                                options.aim_mirrored, options.aim_mirror_normal, options.aim_mirror_offset, {}};
  for (const WbsdfRunOptions::AimZone& z : options.aim_more) {
    transport::EmissionTarget more = aim;
    more.origin = z.origin, more.ex = z.ex, more.ey = z.ey, more.half_x_m = z.half_x_m, more.half_y_m = z.half_y_m;
    aim.also.push_back(more);
  }
  if (options.aim) opt.aim = &aim;
  const transport::RoomTraceResult r = transport::traceRoom(room, geometry, source, opt);

  WbsdfLevels out;
  out.rays = r.rays;
  out.occluder_events = r.occluder_events;
  out.evanescent = r.evanescent;
  out.escaped = r.escaped;
  out.seconds = r.seconds;
  const room::Source& src = room.sources[source];
  for (std::size_t l = 0; l < room.listeners.size(); ++l) {
    const core::Vec3 to = room.listeners[l].position_m - src.position_m;
    const double r2 = to.squaredNorm();
    const double gain = transport::directivityGain(src.directivity, to.normalized().dot(src.directivity.axis.normalized()));
    const double free = src.power_w * gain / r2;
    std::vector<BandLevel> bands;
    for (int b = 0; b < room.bands.size(); ++b) {
      BandLevel bl;
      bl.ratio = r.listeners[l].value(b, 0) / free;
      bl.ratio_std_error = r.listeners[l].standardError(b, 0) / free;
      bl.level_db = levelDb(bl.ratio);
      bands.push_back(bl);
    }
    out.listeners.push_back(bands);
  }
  return out;
}

}  // namespace diffray::compare
