#include "diffray/validate/room_setup.h"

#include <cmath>

#include "diffray/core/error.h"

namespace diffray::validate {

std::vector<ParamSpec> shoeboxParams(double absorption, double scattering, double radius_m) {
  std::vector<ParamSpec> ps{
      {"dims", {10, 7, 3}, "room size x y z (m)"},
      {"source", {2, 3, 1.5}, "source position (m)"},
      {"listener", {7, 4, 1.2}, "listener position (m)"},
      {"radius", {radius_m}, "listener sphere radius (m)"},
      {"absorption", {absorption}, "wall absorption: one value, or 8 (octave bands 63 Hz-8 kHz)", 0.0, true, 1.0},
      {"scattering", {scattering}, "wall scattering coefficient", 0.0, true, 1.0 + 1e-12}};
  for (ParamSpec& p : ps)  // three coordinates; 1 or 8 absorptions
    p.list = p.name == "dims" || p.name == "source" || p.name == "listener" || p.name == "absorption";
  return ps;
}

ShoeboxSpec shoeboxFromParams(const Params& p) {
  ShoeboxSpec s;
  const auto three = [&](const std::string& name, std::array<double, 3>& out) {
    const auto& v = p.at(name);
    if (v.size() != 3) throw core::InputError("--" + name, "needs three values (x y z)");
    for (int i = 0; i < 3; ++i) out[i] = v[i];
  };
  three("dims", s.dims_m);
  three("source", s.source_m);
  three("listener", s.listener_m);
  s.radius_m = p.at("radius")[0];
  s.absorption = p.at("absorption");
  if (s.absorption.size() != 1 && s.absorption.size() != 8)
    throw core::InputError("--absorption", "needs 1 or 8 values (octave bands 63 Hz-8 kHz)");
  s.scattering = p.at("scattering")[0];
  for (int i = 0; i < 3; ++i) {
    const bool src_in = s.source_m[i] > 0 && s.source_m[i] < s.dims_m[i];
    const bool lis_in = s.listener_m[i] - s.radius_m > 0 && s.listener_m[i] + s.radius_m < s.dims_m[i];
    if (!src_in) throw core::InputError("--source", "must be inside the room");
    if (!lis_in) throw core::InputError("--listener", "the listener sphere must be inside the room");
  }
  const double sep = std::hypot(s.source_m[0] - s.listener_m[0], s.source_m[1] - s.listener_m[1],
                                s.source_m[2] - s.listener_m[2]);
  if (!(sep > s.radius_m)) throw core::InputError("--listener", "the source is inside the listener sphere");
  return s;
}

room::Room makeShoebox(const ShoeboxSpec& spec) {
  room::Room r;
  r.name = "shoebox";
  int walls[6];
  for (int w = 0; w < 6; ++w) {
    room::Material m;
    m.name = "wall" + std::to_string(w);
    for (int b = 0; b < r.bands.size(); ++b) {
      const double a = spec.absorption.size() == 1 ? spec.absorption[0] : spec.absorption[b];
      m.absorption[b] = std::min(1.0, a * (1.0 + spec.wall_spread * w));
      m.scattering[b] = spec.scattering;
    }
    walls[w] = r.addMaterial(m);
  }
  r.addBox(core::Vec3(0, 0, 0), core::Vec3(spec.dims_m[0], spec.dims_m[1], spec.dims_m[2]), walls);
  room::Source s;
  s.name = "S";
  s.position_m = core::Vec3(spec.source_m[0], spec.source_m[1], spec.source_m[2]);
  r.sources.push_back(s);
  room::Listener l;
  l.name = "L";
  l.position_m = core::Vec3(spec.listener_m[0], spec.listener_m[1], spec.listener_m[2]);
  l.radius_m = spec.radius_m;
  r.listeners.push_back(l);
  return r;
}

std::array<std::vector<double>, 6> specularFactors(const room::Room& room) {
  std::array<std::vector<double>, 6> out;
  for (int w = 0; w < 6; ++w)
    for (int b = 0; b < room.bands.size(); ++b)
      out[w].push_back((1.0 - room.materials[w].absorption[b]) * (1.0 - room.materials[w].scattering[b]));
  return out;
}

std::vector<double> schroederDb(const std::vector<double>& energy) {
  std::vector<double> tail(energy.size());
  double sum = 0.0;
  for (std::size_t i = energy.size(); i-- > 0;) {
    sum += energy[i];
    tail[i] = sum;
  }
  for (double& v : tail) v = v > 0.0 && sum > 0.0 ? 10.0 * std::log10(v / sum) : -1e300;
  return tail;
}

}  // namespace diffray::validate
