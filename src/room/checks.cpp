#include "diffray/room/checks.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include "diffray/core/error.h"
#include "diffray/room/json_fields.h"

namespace diffray::room {
namespace {

using core::Vec3;

std::string format(const Vec3& p) {
  std::ostringstream s;
  s << "(" << p.x() << ", " << p.y() << ", " << p.z() << ")";
  return s.str();
}

}  // namespace

bool crossesTriangle(const Vec3& o, const Vec3& d, const Vec3& a, const Vec3& b, const Vec3& c, double t_lo,
                     double t_hi) {
  const double t = geometry::rayTriangleT(o, d, a, b, c);  // NaN (no hit) fails both comparisons
  return t > t_lo && t < t_hi;
}

// Closest point on triangle abc to p (Ericson, Real-Time Collision Detection, §5.1.5).
Vec3 closestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

int openEdgeCount(const Room& room) {
  const auto& m = room.mesh;
  if (m.triangles.empty()) return 0;
  // Weld vertices by position on a grid of cell `tol`, looking into neighbouring cells so that two
  // copies of a corner computed in different orders (1 ulp apart) always meet.
  Vec3 lo = m.vertices[0], hi = m.vertices[0];
  for (const auto& v : m.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  const double tol = std::max(1e-6 * (hi - lo).norm(), 1e-12);
  using Cell = std::array<long long, 3>;
  std::map<Cell, std::vector<int>> grid;
  std::vector<int> id(m.vertices.size());
  for (std::size_t i = 0; i < m.vertices.size(); ++i) {
    const Vec3& v = m.vertices[i];
    const Cell c = {std::llround(v.x() / tol), std::llround(v.y() / tol), std::llround(v.z() / tol)};
    int found = -1;
    for (long long dx = -1; dx <= 1 && found < 0; ++dx)
      for (long long dy = -1; dy <= 1 && found < 0; ++dy)
        for (long long dz = -1; dz <= 1 && found < 0; ++dz) {
          const auto it = grid.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == grid.end()) continue;
          for (int j : it->second)
            if ((m.vertices[j] - v).norm() <= tol) {
              found = id[j];
              break;
            }
        }
    id[i] = found >= 0 ? found : static_cast<int>(i);
    grid[c].push_back(static_cast<int>(i));
  }
  const std::vector<char> bounding = room.enclosure();
  std::map<std::pair<int, int>, int> uses;
  for (std::size_t t = 0; t < m.triangles.size(); ++t) {
    if (!bounding[t]) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = id[m.triangles[t][k]], b = id[m.triangles[t][(k + 1) % 3]];
      if (a != b) ++uses[{std::min(a, b), std::max(a, b)}];
    }
  }
  return static_cast<int>(std::count_if(uses.begin(), uses.end(), [](const auto& e) { return e.second == 1; }));
}

bool insideRoom(const Room& room, const Vec3& p) {
  // Directions with no special relation to axis-aligned geometry, so that a ray rarely grazes an edge.
  static const Vec3 dirs[3] = {Vec3(0.5773, 0.5819, 0.5727).normalized(), Vec3(-0.3123, 0.8761, 0.3672).normalized(),
                               Vec3(0.2113, -0.4477, -0.8689).normalized()};
  const auto& m = room.mesh;
  const std::vector<char> bounding = room.enclosure();
  int votes = 0;
  for (const Vec3& d : dirs) {
    int count = 0;
    for (std::size_t t = 0; t < m.triangles.size(); ++t)
      if (bounding[t] && crossesTriangle(p, d, m.vertices[m.triangles[t][0]], m.vertices[m.triangles[t][1]],
                                         m.vertices[m.triangles[t][2]]))
        ++count;
    votes += count % 2;
  }
  return votes >= 2;
}

double distanceToSurface(const Room& room, const Vec3& p) {
  const auto& m = room.mesh;
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : m.triangles)
    best = std::min(best, (p - closestOnTriangle(p, m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]])).norm());
  return best;
}

std::vector<std::string> roomWarnings(const Room& room) {
  std::vector<std::string> w;
  if (const int open = openEdgeCount(room); open > 0)
    w.push_back("the mesh is not closed: " + std::to_string(open) +
                " edge(s) belong to only one surface triangle, so rays may leak out");
  for (const Source& s : room.sources) {
    const std::string what = "source " + s.name + " at " + format(s.position_m);
    if (!insideRoom(room, s.position_m)) w.push_back(what + " is outside the room");
    const double d = distanceToSurface(room, s.position_m);
    if (d < 0.01) w.push_back(what + " is " + formatNumber(std::round(d * 1e4) / 10.0) + " mm from a surface (< 1 cm)");
  }
  for (const Listener& l : room.listeners) {
    const std::string what = "listener " + l.name + " at " + format(l.position_m);
    if (!insideRoom(room, l.position_m)) w.push_back(what + " is outside the room");
    const double d = distanceToSurface(room, l.position_m);
    if (d < l.radius_m)
      w.push_back(what + ": its sphere (radius " + formatNumber(l.radius_m) + " m) is cut by a surface " +
                  formatNumber(std::round(d * 1e4) / 1e4) + " m from its centre");
    // The direct sound is the image-source value P/d² at the centre: it grows without bound as the source
    // nears the centre, and at the centre itself there is none (the rays leave it to the image sources).
    for (const Source& s : room.sources) {
      const double r = (s.position_m - l.position_m).norm();
      if (r < l.radius_m)
        w.push_back(what + ": source " + s.name + " lies inside its sphere, " + formatNumber(std::round(r * 1e4) / 1e4) +
                    " m from the centre" + (r > 0.0 ? " (the direct sound is P/d² there)" : ": the direct sound is left out") +
                    "; move them apart");
    }
  }
  return w;
}

void checkSynthesis(const Room& room, double length_s, double sample_rate_hz, const std::string& rate_field) {
  const std::string where = room.file.empty() ? "room" : room.file;
  const double fs = sample_rate_hz;
  const int top = room.bands.size() - 1;
  if (!(room.bands.upperHz(top) < 0.5 * fs))
    throw core::InputError(rate_field, "the " + room.bands.label(top) + " Hz band reaches past the Nyquist frequency of " +
                                           std::to_string(static_cast<long>(fs)) + " Hz; raise the sample rate");
  if (!(room.volume() > 0.0))
    throw core::InputError(where, "the geometry encloses no volume, which the IR synthesis needs (V in the "
                                  "reflection density 4πc³t²/V)");
  // Longest possible IR: --length, the file's length, or (auto) max_length_s.
  const double longest = length_s > 0 ? length_s : (room.output.ir_length_s > 0 ? room.output.ir_length_s
                                                                                 : room.output.max_length_s);
  constexpr double kMaxFrames = 33554432.0;  // 2^25 frames: ~12 min at 48 kHz, a few GB while synthesizing
  if (longest * fs > kMaxFrames)
    throw core::InputError(where + ": output", "an IR of " + std::to_string(longest) + " s at " +
                                                   std::to_string(static_cast<long>(fs)) +
                                                   " Hz is over 2^25 samples; shorten max_length_s/ir_length_s");
}

}  // namespace diffray::room
