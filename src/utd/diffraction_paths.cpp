// The diffracted paths of the UTD model (utd/paths.h): first- and second-order edge diffraction, each edge
// optionally with a first-order specular reflection before it, after it and (second order) between the
// edges. A reflection is unfolded by the image principle (a ray reflected off a plane continues straight from
// the image of where it came from), so the apexes are the ones of the plain path from the source's image
// through the edges (the second edge mirrored when a reflection lies between them) to the listener's image,
// and Keller's law of edge diffraction holds on the unfolded path (Keller, J. Opt. Soc. Am. 52, 1962).
#include <algorithm>
#include <cmath>
#include <vector>

#include "diffray/utd/apex.h"
#include "path_util.h"

namespace diffray::utd {

using core::Vec3;
using detail::mirror;
using detail::signedDistance;
using transport::MirrorPlane;

namespace {

Vec3 mirrorDirection(const MirrorPlane& pl, const Vec3& v) { return v - 2.0 * pl.normal.dot(v) * pl.normal; }

// Edge e mirrored in plane pl: its image's points are the images of its points at the same arc length (the
// apex solvers use start, tangent and length only).
Edge mirroredEdge(const Edge& e, const MirrorPlane& pl) {
  Edge m = e;
  m.start = mirror(pl, e.start);
  m.end = mirror(pl, e.end);
  m.tangent = mirrorDirection(pl, e.tangent);
  return m;
}

// A vertex of a candidate path: the source, an apex, a reflection point or the listener.
struct Vertex {
  Vec3 p{0, 0, 0};
  int edge = -1;             ///< an apex: its edge
  int triangle = -1;         ///< a reflection point: its triangle
  Vec3 lift{0, 0, 0};        ///< off the planes the vertex lies on, into the air on the path's side (m)
};

// A face of an edge along which a leg leaving the apex in unit direction u runs (u lies in the face's
// half-plane): its φ and air normal.
struct Along {
  double phi;
  Vec3 normal;
};

std::vector<Along> facesAlong(const Edge& e, const Vec3& u) {
  std::vector<Along> out;
  const Vec3 across = u - u.dot(e.tangent) * e.tangent;  // the leg's direction about the edge
  const double size = across.norm();
  if (!(size > 1e-9)) return out;
  if (across.dot(e.face0_dir) > (1.0 - 1e-12) * size) out.push_back({0.0, e.normal0});
  if (across.dot(e.facen_dir) > (1.0 - 1e-12) * size) out.push_back({e.wedge_n * core::kPi, e.normaln});
  return out;
}

}  // namespace

void UtdModel::addDiffractions(int order, const Vec3& s, const Vec3& r, std::vector<Path>& out) const {
  const auto& planes = geometry_.planes();
  const int n_e = static_cast<int>(edges_.size());
  const int n_p = options_.reflected_diffraction ? static_cast<int>(planes.size()) : 0;
  // An edge lying in a plane (a face of it is there, or it is a foot on it) does not reflect off it: that
  // reflection is part of its D.
  std::vector<char> holds(static_cast<std::size_t>(n_e) * n_p, 0);
  const auto on = [&](int k, const Vec3& x) { return std::abs(signedDistance(planes[k], x)) <= offsetAt(x); };
  for (int e = 0; e < n_e; ++e)
    for (int k = 0; k < n_p; ++k) holds[e * n_p + k] = on(k, edges_[e].start) && on(k, edges_[e].end);
  // +1 or −1 when the whole of edge e lies strictly on that side of plane k, else 0.
  const auto sideOf = [&](int k, int e) {
    const double a = signedDistance(planes[k], edges_[e].start), b = signedDistance(planes[k], edges_[e].end);
    if (a > offsetAt(edges_[e].start) && b > offsetAt(edges_[e].end)) return 1;
    if (-a > offsetAt(edges_[e].start) && -b > offsetAt(edges_[e].end)) return -1;
    return 0;
  };
  // No reflection off plane k between point x and edge e when they lie strictly on opposite sides of it.
  const auto apart = [&](int k, const Vec3& x, int e) {
    const double d = signedDistance(planes[k], x);
    const int side = sideOf(k, e);
    return std::abs(d) > offsetAt(x) && side != 0 && (d > 0.0) != (side > 0);
  };
  const auto excluded = [&](int k, const Vec3& x, int e) { return k >= 0 && (holds[e * n_p + k] || apart(k, x, e)); };
  Candidate c;
  c.order = order;
  if (order == 1) {
    for (int e = 0; e < n_e; ++e)
      for (int m0 = -1; m0 < n_p; ++m0) {
        if (excluded(m0, s, e)) continue;
        for (int m1 = -1; m1 < n_p; ++m1) {
          if (excluded(m1, r, e)) continue;
          c.edge[0] = e;
          c.mirror[0] = m0;
          c.mirror[1] = m1;
          tryCandidate(c, s, r, out);
        }
      }
    return;
  }
  const int most = options_.second_order_reflections;
  for (int e0 = 0; e0 < n_e; ++e0)
    for (int e1 = 0; e1 < n_e; ++e1)
      for (int m0 = -1; m0 < n_p; ++m0) {
        if (excluded(m0, s, e0) || (m0 >= 0) > most) continue;
        for (int m1 = -1; m1 < n_p; ++m1) {
          if ((m0 >= 0) + (m1 >= 0) > most) break;
          if (m1 < 0 ? e0 == e1
                     : holds[e0 * n_p + m1] || holds[e1 * n_p + m1] || sideOf(m1, e0) * sideOf(m1, e1) < 0)
            continue;  // the same edge twice only with a reflection between
          for (int m2 = -1; m2 < n_p; ++m2) {
            if ((m0 >= 0) + (m1 >= 0) + (m2 >= 0) > most) break;
            if (excluded(m2, r, e1)) continue;
            c.edge[0] = e0;
            c.edge[1] = e1;
            c.mirror[0] = m0;
            c.mirror[1] = m1;
            c.mirror[2] = m2;
            tryCandidate(c, s, r, out);
          }
        }
      }
}

void UtdModel::tryCandidate(const Candidate& c, const Vec3& s, const Vec3& r, std::vector<Path>& out) const {
  const auto& planes = geometry_.planes();
  const int n = c.order, m_before = c.mirror[0], m_between = n == 2 ? c.mirror[1] : -1, m_after = c.mirror[n];
  // The unfolded path: the source's image a, the apexes, the listener as seen from the last apex.
  const Vec3 a = m_before >= 0 ? mirror(planes[m_before], s) : s;
  const Vec3 r_seen = m_after >= 0 ? mirror(planes[m_after], r) : r;
  Vec3 q[2], from[2], to[2];
  double arc = 0.0, arc1 = 0.0;  // the apexes' arc lengths on their edges
  bool on_edge = true;  // false: the apex lies beyond a free end (a corner's wave, finite_edges)
  if (n == 1) {
    const Edge& e = edges_[c.edge[0]];
    if (!apexOnLine(e, a, r_seen, arc)) return;
    const double tol = 1e-9 * e.length_m;
    on_edge = arc >= -tol && arc <= e.length_m + tol;
    if (on_edge) arc = std::clamp(arc, 0.0, e.length_m);
    if (!on_edge && !options_.finite_edges) return;
    q[0] = e.at(arc);
    from[0] = a;
    to[0] = r_seen;
  } else {
    const Edge& e0 = edges_[c.edge[0]];
    const Edge& e1 = edges_[c.edge[1]];
    const Edge e1_seen = m_between >= 0 ? mirroredEdge(e1, planes[m_between]) : e1;
    // Collinear pieces (or an edge and its own image on its line): no path between them leaves the line.
    if (e0.tangent.cross(e1_seen.tangent).norm() < 1e-9 &&
        (e1_seen.start - e0.start).cross(e0.tangent).norm() < offsetAt(e1_seen.start))
      return;
    const Vec3 b = m_between >= 0 ? mirror(planes[m_between], r_seen) : r_seen;
    double t0, t1;
    if (!apexesOnEdges(e0, e1_seen, a, b, t0, t1)) return;
    q[0] = e0.at(t0);
    q[1] = e1.at(t1);
    arc = t0;
    arc1 = t1;
    from[0] = a;
    to[0] = e1_seen.at(t1);
    from[1] = m_between >= 0 ? mirror(planes[m_between], q[0]) : q[0];
    to[1] = r_seen;
  }
  const double s_in = (q[0] - from[0]).norm(), s_out = (to[n - 1] - q[n - 1]).norm();
  const double s_mid = n == 2 ? (to[0] - q[0]).norm() : 0.0;
  if (!(s_in > 0.0 && s_out > 0.0) || (n == 2 && !(s_mid > offsetAt(q[0])))) return;

  // The real vertices, with a reflection point wherever the path meets a plane between two of them.
  std::vector<Vertex> v;
  v.push_back({s});
  const auto bounce = [&](int k, const Vec3& x, const Vec3& y) {
    if (k < 0) return true;
    const MirrorPlane& pl = planes[k];
    const double dx = signedDistance(pl, x), dy = signedDistance(pl, y);
    const bool x_on = std::abs(dx) <= offsetAt(x), y_on = std::abs(dy) <= offsetAt(y);
    if ((x_on && y_on) || (!x_on && !y_on && dx * dy < 0.0)) return false;  // both on it, or on opposite sides
    const double side = std::abs(dx) >= std::abs(dy) ? (dx >= 0.0 ? 1.0 : -1.0) : (dy >= 0.0 ? 1.0 : -1.0);
    const double ax = std::max(side * dx, 0.0), ay = std::max(side * dy, 0.0);
    Vec3 p = x + (ax / (ax + ay)) * (mirror(pl, y) - x);
    p -= signedDistance(pl, p) * pl.normal;
    const int tri = triangleAt(k, p);
    if (tri < 0 || crossesSurfaceAt(pl, p, x, y)) return false;
    if ((p - x).norm() > offsetAt(p) && (p - y).norm() > offsetAt(p) && onEdge(p)) return false;
    v.push_back({p, -1, tri, side * offsetAt(p) * pl.normal});
    return true;
  };
  if (!bounce(m_before, s, q[0])) return;
  v.push_back({q[0], c.edge[0]});
  const std::size_t apex0 = v.size() - 1;
  if (n == 2) {
    if (!bounce(m_between, q[0], q[1])) return;
    v.push_back({q[1], c.edge[1]});
  }
  const std::size_t apex_last = v.size() - 1;
  if (!bounce(m_after, q[n - 1], r)) return;
  v.push_back({r});
  // A reflection point on an apex (an edge standing on the plane, the apex at its foot): the path through
  // the edge and its image is one path, kept as the reflection before the apex; its points are lifted off
  // both the plane and the edge.
  for (std::size_t i = 1; i + 1 < v.size(); ++i) {
    if (v[i].triangle < 0) continue;
    const double off = offsetAt(v[i].p);
    if (v[i - 1].edge >= 0 && (v[i].p - v[i - 1].p).norm() <= off) return;
    if (v[i + 1].edge >= 0 && (v[i].p - v[i + 1].p).norm() <= off) {
      v[i + 1].lift += v[i].lift;
      v[i].lift += off * edges_[v[i + 1].edge].bisector();
    }
  }

  // The faces a leg between two edges runs along: on a thin plate, one path along each of its faces.
  struct Variant {
    double phi_out0, phi_in1;
    Vec3 side0{0, 0, 0}, side1{0, 0, 0};  ///< unit air normals of the faces the middle leg runs along
  };
  std::vector<Variant> variants;
  const double phi_in0 = phiOf(c.edge[0], from[0]), phi_out_last = phiOf(c.edge[n - 1], to[n - 1]);
  if (n == 1) {
    variants.push_back({phi_out_last, 0.0});
  } else {
    const auto along0 = facesAlong(edges_[c.edge[0]], (to[0] - q[0]).normalized());
    const auto along1 = facesAlong(edges_[c.edge[1]], (from[1] - q[1]).normalized());
    for (const Along& f0 : along0)
      for (const Along& f1 : along1) {
        const Vec3 seen = m_between >= 0 ? mirrorDirection(planes[m_between], f0.normal) : f0.normal;
        if (seen.dot(f1.normal) > 0.5) variants.push_back({f0.phi, f1.phi, f0.normal, f1.normal});
      }
    if (along0.empty() || along1.empty()) variants.push_back({phiOf(c.edge[0], to[0]), phiOf(c.edge[1], from[1])});
  }

  for (const Variant& var : variants) {
    Diffraction d[2];
    if (n == 1) {
      if (!diffraction(c.edge[0], q[0], from[0], phi_in0, var.phi_out0, s_in * s_out / (s_in + s_out), d[0])) continue;
      d[0].arc_m = arc;
      d[0].curvature = std::pow(std::sin(d[0].beta0), 2) * (1.0 / s_in + 1.0 / s_out);
      if (!on_edge && !keepsCorner(c.edge[0], arc, d[0].curvature)) continue;
    } else {
      const double rho = s_in + s_mid;
      if (!diffraction(c.edge[0], q[0], from[0], phi_in0, var.phi_out0, s_in * s_mid / rho, d[0]) ||
          !diffraction(c.edge[1], q[1], from[1], var.phi_in1, phi_out_last, rho * s_out / (rho + s_out), d[1]))
        continue;
      d[0].arc_m = arc;
      d[1].arc_m = arc1;
    }
    // Every leg in the clear, between points lifted off what they lie on; a leg along a face is lifted off
    // it on its side (instead of along the bisector at its apexes).
    bool clear = true;
    for (std::size_t k = 0; k + 1 < v.size() && clear; ++k) {
      const Vertex &x = v[k], &y = v[k + 1];
      if ((y.p - x.p).norm() <= std::max(offsetAt(x.p), offsetAt(y.p))) continue;  // a reflection on s, r or an apex
      const bool middle = n == 2 && k >= apex0 && k < apex_last;
      const Vec3 side = !middle ? Vec3(0, 0, 0) : (k + 1 == apex_last ? var.side1 : var.side0);
      const auto end = [&](const Vertex& w, const Vec3& nu) {
        // An apex beyond the edge's end is seen through the end (the corner).
        Vec3 p = (w.edge >= 0 && !on_edge ? edges_[w.edge].at(std::clamp(arc, 0.0, edges_[w.edge].length_m)) : w.p) + w.lift;
        if (nu.squaredNorm() > 0.0)
          p += offsetAt(w.p) * nu;
        else if (w.edge >= 0)
          p += offsetAt(w.p) * edges_[w.edge].bisector();
        return p;
      };
      clear = visible(end(x, side), end(y, side));
    }
    if (!clear) continue;
    Path path;
    path.kind = PathKind::Diffraction;
    path.order = n;
    for (std::size_t i = 0; i < v.size(); ++i) {
      path.points.push_back(v[i].p);
      if (i > 0) path.length_m += (v[i].p - v[i - 1].p).norm();
      if (v[i].triangle >= 0) path.bounces.push_back({v[i].triangle, static_cast<int>(i)});
      if (v[i].edge >= 0) {
        const int j = static_cast<int>(path.edges.size());
        path.edges.push_back(v[i].edge);
        d[j].point = static_cast<int>(i);
        path.diffractions.push_back(d[j]);
      }
    }
    out.push_back(std::move(path));
  }
}

}  // namespace diffray::utd
