#pragma once
// Diffraction points by Fermat's principle: the path a → edge → b (or a → edge 1 → edge 2
// → b) of least length through points of the edges' lines. On a straight edge the least path meets the
// edge on Keller's cone: the rays make equal angles with the edge. Results are arc lengths from each edge's
// start; a solution is returned only if it lies on the segments [0, length_m] (within 1e-9 × length).
// Units: metres. Pure functions; thread-safe.
#include "diffray/utd/edges.h"

namespace diffray::utd {

/// First order: the point at arc length s_m on `edge` minimising |a − Q| + |Q − b| (closed form: the
/// unfolded straight line). False if a and b both lie on the edge's line or the point is off the segment.
bool apexOnEdge(const Edge& edge, const Vec3& a, const Vec3& b, double& s_m);
/// The same point on the edge's whole line (s_m may lie beyond the ends); false only if a and b both lie on it.
bool apexOnLine(const Edge& edge, const Vec3& a, const Vec3& b, double& s_m);

/// Second order: arc lengths s1_m, s2_m minimising |a − Q1| + |Q1 − Q2| + |Q2 − b| (convex; damped Newton).
/// False if it does not converge or either point is off its segment.
bool apexesOnEdges(const Edge& e1, const Edge& e2, const Vec3& a, const Vec3& b, double& s1_m, double& s2_m);

}  // namespace diffray::utd
