#pragma once
// The FDTD wave reference (reference/fdtd.h) as the wave model of a room comparison (compare/room_compare.h):
// its energy histograms per listener and band in the comparison's layout, the bands it does not simulate left
// empty (their figures NaN, no difference formed). Both sides use the same units: a 1 W omnidirectional
// source gives 1/r² J/m² in free field, time 0 at emission.
#include "diffray/compare/room_compare.h"
#include "diffray/reference/fdtd.h"

namespace diffray::compare {

/// `result` (of simulateWave on `room`) as ListenerHistograms: [listener][band of room.bands][bin].
ListenerHistograms waveHistograms(const room::Room& room, const reference::WaveResult& result);

/// A HistogramModel that runs simulateWave with `options` (its callbacks included) on the room it is given.
HistogramModel waveModel(reference::WaveOptions options);

}  // namespace diffray::compare
