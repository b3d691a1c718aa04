#pragma once
// Geometric sanity checks of a room, reported as warnings (the run goes on; the tracer measures the
// energy a leak actually loses): an open mesh, sources and listeners outside the enclosure, a listener
// sphere cut by a surface, a source closer than 1 cm to a surface. The edge count and the inside test
// use Room::enclosure(): an opening between two rooms is left out, one that closes the room (an open
// window to the outside) is kept, so neither counts as a hole. Brute force over the triangles: meant
// for scene loading, not for tracing.
// Free functions on a const Room; thread-safe.
#include <limits>
#include <string>
#include <vector>

#include "diffray/room/room.h"

namespace diffray::room {

/// Edges (after welding vertices closer than 1e-6 of the scene size) used by exactly one triangle of
/// Room::enclosure().
int openEdgeCount(const Room& room);
/// Whether `p` is inside the enclosure: the parity of crossings along three fixed directions, majority.
bool insideRoom(const Room& room, const core::Vec3& p);
/// Whether o + t·d meets triangle abc (edges included) at some t with t_lo < t < t_hi (Möller–Trumbore,
/// in double): the default is the open ray.
bool crossesTriangle(const core::Vec3& o, const core::Vec3& d, const core::Vec3& a, const core::Vec3& b,
                     const core::Vec3& c, double t_lo = 0.0,
                     double t_hi = std::numeric_limits<double>::infinity());
/// The point of triangle abc closest to p (Ericson, Real-Time Collision Detection, §5.1.5).
core::Vec3 closestOnTriangle(const core::Vec3& p, const core::Vec3& a, const core::Vec3& b, const core::Vec3& c);
/// The distance (m) from `p` to the nearest triangle, openings included; +inf for an empty mesh.
double distanceToSurface(const Room& room, const core::Vec3& p);

/// One line per problem found (empty when none).
std::vector<std::string> roomWarnings(const Room& room);

/// What IR synthesis will need, checked before a (long) trace rather than after it: the room's top band below
/// the Nyquist frequency of `sample_rate_hz` (else an InputError naming `rate_field`), an enclosed volume, and
/// an IR (`length_s`, or the room file's) of at most 2^25 samples.
void checkSynthesis(const Room& room, double length_s, double sample_rate_hz, const std::string& rate_field);

}  // namespace diffray::room
