#pragma once
// The image-source method for any room made of planar triangles (Allen & Berkley 1979 for the images,
// Borish 1984 for polyhedra): the source is mirrored across the room's planes (RoomGeometry::planes) up to
// `max_order` reflections, never twice in a row across the same plane, and every candidate path is
// validated by tracing it back from the listener with the intersector: each reflection point must lie on
// a triangle of its plane, and no surface may block a leg (surfaces that transmit everything, openings, do
// not block), nor a surface on the mirror's air side whose plane the path crosses at the reflection point
// itself (a side wall's reflection where a partition joins it: the intersector cannot see a crossing at a
// leg's end). A valid path arrives at its exact delay d/c with, per band, the energy
// P·D(θ)·Π(1 − α)(1 − s)·e^{−m d}/d² (the specular part of each reflection; J/m² for a 1 W omni source at
// d = 1 m giving 1), so together with transport/room_tracer.h, which leaves exactly these paths out, no
// path is counted twice. Units: metres, seconds. Pure function; thread-safe.
#include <vector>

#include "diffray/ir/response.h"
#include "diffray/room/room.h"
#include "diffray/transport/room_geometry.h"

namespace diffray::transport {

struct ImageSourceOptions {
  int max_order = 3;
  double length_s = 1.0;  ///< arrivals later than this are dropped
  double speed_of_sound_m_s = 343.0;
  core::BandArray air_m_per_m = core::bandFill(0.0);
  /// Refuse (InputError) above this many candidate image sources: planes·(planes − 1)^(order − 1) grows fast.
  double max_candidates = 5e6;
  /// Per triangle, 1 where a path may not pass even if the material is an opening: the WBSDF occluders when
  /// diffraction is on (RoomOccluders::triangleMask), whose rays the tracer follows instead. Null: none.
  const std::vector<char>* blocking_triangles = nullptr;
};

/// Valid specular paths (order 0 = direct sound) from source `source` to listener `listener`, by delay.
std::vector<ir::Arrival> imageSources(const room::Room& room, const RoomGeometry& geometry, int source,
                                      int listener, const ImageSourceOptions& options);

}  // namespace diffray::transport
