#include "diffray/utd/edges.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <tuple>

#include "diffray/core/error.h"

namespace diffray::utd {

double Edge::phi(const Vec3& p) const {
  const Vec3 v = p - start;
  const double a = std::atan2(v.dot(normal0), v.dot(face0_dir));
  return a < 0.0 ? a + core::kTwoPi : a;
}

Vec3 Edge::bisector() const {
  const double half = 0.5 * wedge_n * core::kPi;
  return (std::cos(half) * face0_dir + std::sin(half) * normal0).normalized();
}

namespace {

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(std::size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  }
  void unite(int a, int b) {
    a = find(a);
    b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  }
};

// Vertices merged when closer than `tol` (a grid of cells of size tol; the 27 neighbouring cells are
// searched, so no pair is split by a cell boundary).
std::vector<int> weldVertices(const std::vector<Vec3>& vertices, double tol, std::vector<Vec3>& welded) {
  std::map<std::array<long, 3>, std::vector<int>> cells;
  std::vector<int> id(vertices.size());
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    const Vec3& v = vertices[i];
    const std::array<long, 3> c{std::lround(v.x() / tol), std::lround(v.y() / tol), std::lround(v.z() / tol)};
    int found = -1;
    for (long dx = -1; dx <= 1 && found < 0; ++dx)
      for (long dy = -1; dy <= 1 && found < 0; ++dy)
        for (long dz = -1; dz <= 1 && found < 0; ++dz) {
          auto it = cells.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == cells.end()) continue;
          for (int w : it->second)
            if ((welded[w] - v).norm() <= tol) {
              found = w;
              break;
            }
        }
    if (found < 0) {
      found = static_cast<int>(welded.size());
      welded.push_back(v);
      cells[c].push_back(found);
    }
    id[i] = found;
  }
  return id;
}

struct Segment {
  int a, b;  ///< welded vertex ids
  int tri;   ///< room triangle
  int apex;  ///< the triangle's third welded vertex
};

struct Face {
  double theta;  ///< angle about the chain direction
  Vec3 dir;      ///< unit, ⊥ line, into the triangle
  int tri;
};

// An elementary piece of a straight chain with the triangles around it.
struct Interval {
  int chain;
  double t0, t1;
  std::vector<int> segments;
};

struct Chain {
  Vec3 origin, dir;
};

// A triangle in the plane of a chain that covers its line over [t0, t1] (chain parameter, metres).
struct Coplanar {
  int tri;
  double t0, t1;
};

// The faces around interval iv: the triangle of each of its segments, as the unit direction ⊥ the line from
// the line into the triangle.
std::vector<Face> faceDirs(const Interval& iv, const Chain& ch, const std::vector<Segment>& segs,
                           const std::vector<Vec3>& pos) {
  std::vector<Face> faces;
  for (int s : iv.segments) {
    const Vec3 r = pos[segs[s].apex] - ch.origin;
    faces.push_back({0.0, (r - r.dot(ch.dir) * ch.dir).normalized(), segs[s].tri});
  }
  return faces;
}

// Angles about `axis` from the first face, ascending, duplicates (the same direction) removed.
void sortFaces(std::vector<Face>& faces, const Vec3& axis) {
  if (faces.empty()) return;
  const Vec3 u0 = faces[0].dir, v0 = axis.cross(u0);
  for (Face& f : faces) {
    f.theta = std::atan2(f.dir.dot(v0), f.dir.dot(u0));
    if (f.theta < 0.0) f.theta += core::kTwoPi;
    if (f.theta > core::kTwoPi - 1e-9) f.theta = 0.0;
  }
  std::sort(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return a.theta < b.theta; });
  faces.erase(std::unique(faces.begin(), faces.end(), [](const Face& a, const Face& b) { return b.theta - a.theta < 1e-9; }),
              faces.end());
}

// The largest angular gap between consecutive sorted faces (2π for one face, 0 for none).
double largestGap(const std::vector<Face>& sorted) {
  if (sorted.empty()) return 0.0;
  double gap = sorted.front().theta + core::kTwoPi - sorted.back().theta;
  for (std::size_t i = 0; i + 1 < sorted.size(); ++i) gap = std::max(gap, sorted[i + 1].theta - sorted[i].theta);
  return gap;
}

// Signed distances (m) of p from the three sides of triangle t, positive inside (in its plane).
std::array<double, 3> sideDistances(const geometry::Mesh& mesh, int t, const Vec3& p) {
  const auto& v = mesh.triangles[t];
  const Vec3 a = mesh.vertices[v[0]], b = mesh.vertices[v[1]], c = mesh.vertices[v[2]];
  const Vec3 n = (b - a).cross(c - a).normalized();
  const Vec3 corner[3] = {a, b, c};
  std::array<double, 3> d{};
  for (int i = 0; i < 3; ++i) {
    const Vec3 &p0 = corner[i], &p1 = corner[(i + 1) % 3];
    d[i] = n.cross(p1 - p0).normalized().dot(p - p0);  // the inward normal of side p0 → p1
  }
  return d;
}

// Whether p (in the triangle's plane) lies inside triangle t or within `tol` (m) of it.
bool pointInTriangle(const geometry::Mesh& mesh, int t, const Vec3& p, double tol) {
  const auto d = sideDistances(mesh, t, p);
  return d[0] >= -tol && d[1] >= -tol && d[2] >= -tol;
}

// The parameter range [t0, t1] of the line origin + t·dir (in the triangle's plane) that lies inside
// triangle t (a line along one of its sides, within `tol` (m), counts as inside); false when it is shorter
// than tol.
bool lineInTriangle(const geometry::Mesh& mesh, int t, const Vec3& origin, const Vec3& dir, double tol, double& t0,
                    double& t1) {
  const auto d0 = sideDistances(mesh, t, origin), d1 = sideDistances(mesh, t, origin + dir);
  t0 = -1e300;
  t1 = 1e300;
  for (int i = 0; i < 3; ++i) {
    const double rate = d1[i] - d0[i];  // change of the distance per unit t
    if (std::abs(rate) < 1e-12) {
      if (d0[i] < -tol) return false;
      continue;
    }
    const double at = -d0[i] / rate;  // where the line crosses this side
    if (rate > 0.0)
      t0 = std::max(t0, at);
    else
      t1 = std::min(t1, at);
  }
  return t1 - t0 > tol;
}

}  // namespace

std::vector<Edge> extractEdges(const room::Room& room, const transport::RoomGeometry& geometry,
                               const EdgeOptions& options) {
  const geometry::Mesh& mesh = room.mesh;
  const double extent = geometry.extent();
  const double tol = options.weld_relative * extent;
  std::vector<Vec3> pos;
  const std::vector<int> vid = weldVertices(mesh.vertices, tol, pos);

  // 1. Segments of the surface triangles (openings are not surfaces; degenerate triangles are skipped).
  std::vector<Segment> segs;
  std::vector<std::vector<int>> segs_at(pos.size());
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    if (room.isOpening(mesh.object_of_triangle[i])) continue;
    const auto& t = mesh.triangles[i];
    const std::array<int, 3> w{vid[t[0]], vid[t[1]], vid[t[2]]};
    if (w[0] == w[1] || w[1] == w[2] || w[0] == w[2]) continue;
    if ((pos[w[1]] - pos[w[0]]).cross(pos[w[2]] - pos[w[0]]).norm() <= tol * tol) continue;
    for (int e = 0; e < 3; ++e) {
      const int a = w[e], b = w[(e + 1) % 3];
      segs_at[a].push_back(static_cast<int>(segs.size()));
      segs_at[b].push_back(static_cast<int>(segs.size()));
      segs.push_back({a, b, static_cast<int>(i), w[(e + 2) % 3]});
    }
  }

  // 2. Straight chains: segments that share a vertex and are parallel lie on one line.
  const auto unit = [&](const Segment& s) { return (pos[s.b] - pos[s.a]).normalized(); };
  UnionFind chain_uf(segs.size());
  for (const auto& at : segs_at)
    for (std::size_t i = 0; i < at.size(); ++i)
      for (std::size_t j = i + 1; j < at.size(); ++j)
        if (unit(segs[at[i]]).cross(unit(segs[at[j]])).norm() < 1e-9) chain_uf.unite(at[i], at[j]);
  std::map<int, int> chain_of_root;
  std::vector<Chain> chains;
  std::vector<std::vector<int>> chain_segs;
  for (std::size_t s = 0; s < segs.size(); ++s) {
    auto [it, inserted] = chain_of_root.emplace(chain_uf.find(static_cast<int>(s)), static_cast<int>(chains.size()));
    if (inserted) {
      Vec3 d = unit(segs[s]);
      int lead = 0;
      for (int c = 1; c < 3; ++c)
        if (std::abs(d[c]) > std::abs(d[lead]) + 1e-12) lead = c;
      if (d[lead] < 0) d = -d;
      chains.push_back({pos[segs[s].a], d});
      chain_segs.emplace_back();
    }
    chain_segs[it->second].push_back(static_cast<int>(s));
  }

  // 3. Elementary intervals of each chain between all its segment end points (and the extra cuts of step 3b).
  std::vector<Interval> intervals;
  const auto param_of = [&](const Chain& ch, int v) { return (pos[v] - ch.origin).dot(ch.dir); };
  const auto cutChains = [&](const std::vector<std::vector<double>>& extra_cuts) {
    intervals.clear();
    for (std::size_t c = 0; c < chains.size(); ++c) {
      const Chain& ch = chains[c];
      std::vector<double> bp = extra_cuts[c];
      double lo = 1e300, hi = -1e300;
      for (int s : chain_segs[c])
        for (int v : {segs[s].a, segs[s].b}) {
          bp.push_back(param_of(ch, v));
          lo = std::min(lo, bp.back());
          hi = std::max(hi, bp.back());
        }
      std::sort(bp.begin(), bp.end());
      std::vector<double> cuts;
      for (double t : bp)
        if (t >= lo - tol && t <= hi + tol && (cuts.empty() || t - cuts.back() > tol)) cuts.push_back(t);
      const std::size_t first = intervals.size();
      for (std::size_t k = 0; k + 1 < cuts.size(); ++k) intervals.push_back({static_cast<int>(c), cuts[k], cuts[k + 1], {}});
      const auto cut_index = [&](double t) {
        return static_cast<std::size_t>(std::lower_bound(cuts.begin(), cuts.end(), t - tol) - cuts.begin());
      };
      for (int s : chain_segs[c]) {
        std::size_t k0 = cut_index(param_of(ch, segs[s].a)), k1 = cut_index(param_of(ch, segs[s].b));
        if (k0 > k1) std::swap(k0, k1);
        for (std::size_t k = k0; k < k1; ++k) intervals[first + k].segments.push_back(s);
      }
    }
  };
  std::vector<std::vector<double>> extra_cuts(chains.size());
  cutChains(extra_cuts);

  // 3b. Lines inside other surfaces: a chain that lies in the plane of a triangle it is not an edge of (the
  // foot of a panel standing on a ground whose triangles do not share its vertices) has that triangle on
  // one or both sides as well; such a triangle is a face of the chain where it covers it. Only chains with
  // an interval that could be an edge (an angular gap above π) are searched, in the planes of the geometry
  // (a triangle with a segment on the chain is a face there already). The chain is cut where the coverage
  // starts and ends.
  std::vector<std::vector<Coplanar>> coplanar(chains.size());
  {
    std::vector<char> candidate(chains.size(), 0);
    for (const Interval& iv : intervals) {
      if (candidate[iv.chain]) continue;
      std::vector<Face> faces = faceDirs(iv, chains[iv.chain], segs, pos);
      sortFaces(faces, chains[iv.chain].dir);
      if (!faces.empty() && largestGap(faces) > core::kPi * (1.0 + 1e-9)) candidate[iv.chain] = 1;
    }
    bool any = false;
    for (std::size_t c = 0; c < chains.size(); ++c) {
      if (!candidate[c]) continue;
      const Chain& ch = chains[c];
      std::vector<int> own;
      for (int s : chain_segs[c]) own.push_back(segs[s].tri);
      for (const auto& pl : geometry.planes()) {
        if (std::abs(pl.normal.dot(ch.dir)) > 1e-9 || std::abs(pl.normal.dot(ch.origin) - pl.offset) > tol) continue;
        for (int t : pl.triangles) {
          if (room.isOpening(mesh.object_of_triangle[t]) || std::find(own.begin(), own.end(), t) != own.end()) continue;
          // A triangle that only touches the line at a vertex covers it over a few tolerances: not a face.
          double t0, t1;
          if (!lineInTriangle(mesh, t, ch.origin, ch.dir, tol, t0, t1) || t1 - t0 < 100.0 * tol) continue;
          coplanar[c].push_back({t, t0, t1});
          extra_cuts[c].push_back(t0);
          extra_cuts[c].push_back(t1);
          any = true;
        }
      }
    }
    if (any) cutChains(extra_cuts);
  }

  // 4. Closed parts of the mesh: triangles joined across intervals bordered by exactly two of them; a part
  // is closed when every interval it touches is bordered by an even number of its triangles.
  UnionFind part_uf(mesh.triangles.size());
  for (const Interval& iv : intervals)
    if (iv.segments.size() == 2) part_uf.unite(segs[iv.segments[0]].tri, segs[iv.segments[1]].tri);
  std::vector<char> part_closed(mesh.triangles.size(), 1), used(mesh.triangles.size(), 0);
  for (const Interval& iv : intervals) {
    std::map<int, int> count;
    for (int s : iv.segments) {
      ++count[part_uf.find(segs[s].tri)];
      used[segs[s].tri] = 1;
    }
    for (const auto& [part, n] : count)
      if (n % 2 != 0) part_closed[part] = 0;
  }
  std::vector<char> closed_tri(mesh.triangles.size(), 0);
  bool any_closed = false;
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    closed_tri[i] = used[i] && part_closed[part_uf.find(static_cast<int>(i))];
    any_closed = any_closed || closed_tri[i];
  }

  // 5. Air test: parity of crossings with the closed parts along three generic directions (majority).
  const auto parity = [&](const Vec3& p) {
    static const Vec3 dirs[3] = {Vec3(0.5773, 0.5781, 0.5765).normalized(), Vec3(-0.3111, 0.8123, -0.4932).normalized(),
                                 Vec3(0.7071, -0.2017, 0.6777).normalized()};
    int odd = 0;
    for (const Vec3& d : dirs) {
      int crossings = 0;
      double tnear = 0.0;
      for (int guard = 0; guard < 100000; ++guard) {
        const geometry::Hit hit = geometry.intersector().intersect(geometry::Ray{p, d, tnear, 1e300});
        if (!hit.valid()) break;
        if (closed_tri[hit.triangle]) ++crossings;
        tnear = hit.t * (1.0 + 1e-7) + 1e-7 * extent;
      }
      odd += crossings % 2;
    }
    return odd >= 2 ? 1 : 0;
  };
  int air_parity = any_closed ? 1 : 0;
  if (options.air_point)
    air_parity = parity(*options.air_point);
  else if (!room.sources.empty())
    air_parity = parity(room.sources[0].position_m);
  const double probe = 1e-4 * extent;

  // 6. Wedges per interval, merged along each chain while the two faces stay the same.
  std::vector<Edge> edges;
  int last_interval = -2;
  for (std::size_t k = 0; k < intervals.size(); ++k) {
    const Interval& iv = intervals[k];
    if (iv.segments.empty()) continue;
    const Chain& ch = chains[iv.chain];
    std::vector<Face> faces = faceDirs(iv, ch, segs, pos);
    const double mid_t = 0.5 * (iv.t0 + iv.t1);
    for (const Coplanar& cp : coplanar[iv.chain]) {
      if (mid_t < cp.t0 - tol || mid_t > cp.t1 + tol) continue;
      const Vec3 m = ch.origin + mid_t * ch.dir, w = geometry.triangle(cp.tri).normal.cross(ch.dir).normalized();
      for (const Vec3& dir : {w, Vec3(-w)})
        if (pointInTriangle(mesh, cp.tri, m + 4.0 * tol * dir, 0.5 * tol)) faces.push_back({0.0, dir, cp.tri});
    }
    const Vec3 u0 = faces[0].dir, v0 = ch.dir.cross(u0);
    sortFaces(faces, ch.dir);
    for (std::size_t i = 0; i < faces.size(); ++i) {
      const Face& f0 = faces[i];
      const Face& fn = faces[(i + 1) % faces.size()];
      double gap = fn.theta - f0.theta;
      if (i + 1 == faces.size()) gap += core::kTwoPi;
      if (!(gap > core::kPi * (1.0 + 1e-9))) continue;
      const double mid = f0.theta + 0.5 * gap;
      const Vec3 test = ch.origin + 0.5 * (iv.t0 + iv.t1) * ch.dir + probe * (std::cos(mid) * u0 + std::sin(mid) * v0);
      if (parity(test) != air_parity) continue;
      Edge e;
      e.tangent = ch.dir;
      e.wedge_n = gap / core::kPi;
      e.face0_dir = f0.dir;
      e.facen_dir = fn.dir;
      e.normal0 = ch.dir.cross(f0.dir);
      e.normaln = fn.dir.cross(ch.dir);
      e.triangle0 = f0.tri;
      e.trianglen = fn.tri;
      e.material0 = mesh.object_of_triangle[f0.tri];
      e.materialn = mesh.object_of_triangle[fn.tri];
      e.start = ch.origin + iv.t0 * ch.dir;
      e.end = ch.origin + iv.t1 * ch.dir;
      Edge* prev = edges.empty() ? nullptr : &edges.back();
      const bool same = prev && last_interval == static_cast<int>(k) - 1 && intervals[k - 1].chain == iv.chain &&
                        prev->face0_dir.dot(e.face0_dir) > 1.0 - 1e-12 &&
                        prev->facen_dir.dot(e.facen_dir) > 1.0 - 1e-12 && prev->material0 == e.material0 &&
                        prev->materialn == e.materialn && std::abs(prev->wedge_n - e.wedge_n) < 1e-9;
      if (same)
        prev->end = e.end;
      else
        edges.push_back(e);
      edges.back().length_m = (edges.back().end - edges.back().start).norm();
      last_interval = static_cast<int>(k);
      break;  // the gaps around a line sum to 2π: at most one exceeds π
    }
  }
  return edges;
}

}  // namespace diffray::utd
