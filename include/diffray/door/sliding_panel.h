#pragma once
// A door closed part-way by a sliding panel. The panel enters the opening from
// the jamb toward +ex (the door's frame, room/occluder.h) and covers all of it but a gap of `open_width_m`
// along ex next to the −ex jamb. The room returned has:
//  * the door's opening triangles (its mesh group, and its leaf if it had one) replaced by two rectangles in
//    the opening's plane: the gap, in the opening's own fully transmitting material and under the door's
//    group name, and the panel, in `panel_material` as group "panel:<door>";
//  * the door's occluder narrowed to the gap (origin, half width and x axis [−w/2, w/2]), so that with the
//    WBSDF the gap diffracts as an opening of its width (paper eq. 16 for a slit; the edge kernel of
//    wbsdf/edge_kernel.h), and UTD finds the panel's free edge in the mesh like any other;
//  * with a gap of zero, no occluder for the door (the panel fills the doorway).
// The panel is plain geometry: it reflects and absorbs as its material says; what a shut door transmits is
// added by door/closing.h. Units: metres. Free functions on plain data; thread-safe.
#include <string>

#include "diffray/room/room.h"

namespace diffray::door {

/// Index in room.occluders of the door named `name`, or of the room's only door when `name` is empty.
/// Throws core::InputError (naming --door) when there is no such door, when `name` is empty and the room
/// has no door or several, or when the door is a slit array (only a single opening slides shut).
int findDoor(const room::Room& room, const std::string& name);

/// Gaps narrower than this (m) count as shut: the panel meets the jamb.
inline constexpr double kShutGapM = 1e-4;

/// `room` with door `door` (an index from findDoor) closed by a sliding panel down to a gap of
/// `open_width_m` (0 ≤ open_width_m ≤ the door's width; below kShutGapM the door is shut). `panel_material`
/// is an index into room.materials, or −1 for the door's own panel material (Occluder::panel_material).
/// Throws core::InputError for a width out of range or a door with no panel material.
room::Room withSlidingPanel(const room::Room& room, int door, double open_width_m, int panel_material = -1);

}  // namespace diffray::door
