#pragma once
// The BTM reference benchmarks of diffray_bench (see btm_bench.cpp).

namespace diffray::bench {

/// Prints {"bench":"btm", ...}: the BTM reference (reference/btm_spectrum.h) for the 4 × 2 m rigid plate
/// standing on a rigid ground, second order, `per_octave` frequencies per octave from 100 Hz to 4 kHz at
/// four receivers, beside the anchor: the same field evaluated one frequency at a time
/// (btmPlateOnGroundField) at three of those frequencies, its time per frequency and the largest difference
/// between the two; and UTD on rooms/screen.json (the same plate, ground, source and receivers) at the same
/// frequencies (target 1 s).
void benchBtm(int per_octave);

/// Prints {"bench":"btm-box", ...}: the BTM reference for a rigid 1.2 × 0.6 × 1.8 m box standing on a rigid
/// ground (reference/btm_box.h), second order, `per_octave` frequencies per octave from 100 Hz to 4 kHz at
/// one receiver behind it (btmBoxSpectrum), beside the anchor: btmBoxOnGroundField one frequency at a time
/// at three of those frequencies, its time per frequency and the largest difference between the two.
void benchBtmBox(int per_octave);

}  // namespace diffray::bench
