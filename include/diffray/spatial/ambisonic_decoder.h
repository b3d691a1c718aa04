#pragma once
// Decoding AmbiX signals (ACN order, SN3D; spatial/spherical_harmonics.h) of order 1–3, such as
// `diffray ir --format ambix` impulse responses, to loudspeaker feeds or to the two ears.
//
// Contract.
// - Loudspeakers: a layout of L directions s_j (azimuth counter-clockwise from front, elevation up, degrees;
//   the listener's frame). Mode matching: the feeds g = Y⁺·a, Y the (N+1)² × L matrix of the harmonics at the
//   loudspeakers and Y⁺ its Moore–Penrose pseudo-inverse (Eigen's complete orthogonal decomposition), so
//   that Σ_j g_j·Y(s_j) reproduces the signal's harmonics exactly when L ≥ (N+1)² and Y has full rank, and
//   in the least-squares sense otherwise (Poletti, J. Audio Eng. Soc. 53(11), 2005; Zotter & Frank,
//   "Ambisonics", Springer 2019, ch. 4).
// - Binaural: the same decoding to 2(N+1)² virtual loudspeakers near-uniform over the sphere (a Fibonacci
//   lattice), each moved to the nearest direction the HRTF set measured, each feed convolved with that
//   direction's HRIRs and summed per ear (the virtual-loudspeaker method, Noisternig, Musil, Sontacchi &
//   Höldrich, AES 24th Int. Conf., 2003). Below the order's spatial limit (k·r_head ≤ N: about 1.9 kHz at
//   order 3) the ears' interaural differences follow the field's; above it the decoding blurs them.
// Units follow the input (a feed has the input's unit). Pure functions; thread-safe.
#include <string>
#include <vector>

#include "diffray/core/math.h"

namespace diffray::spatial {

class Hrtf;

/// "AZ:EL,AZ:EL,…" (degrees; EL may be left out, "AZ" meaning elevation 0) as unit vectors in the listener's
/// frame. Throws core::InputError naming `option` for an empty list, a malformed entry or an angle outside
/// [−360, 360] (azimuth) or [−90, 90] (elevation).
std::vector<core::Vec3> parseLayout(const std::string& text, const std::string& option);

/// The Ambisonic order of a signal with `channels` channels: 1, 2 or 3; throws core::InputError naming
/// `what` for any other count ((N+1)² = 4, 9 or 16).
int ambisonicOrderOf(int channels, const std::string& what);

/// The loudspeaker feeds of `ambix` ((N+1)² channels of equal length) for `layout`.
std::vector<std::vector<float>> decodeToLayout(const std::vector<std::vector<float>>& ambix,
                                               const std::vector<core::Vec3>& layout);

/// The two ears' signals (left, right) of `ambix` through `hrtf` (prepared at the signal's rate); each is the
/// input's length plus the HRIRs' minus one.
std::vector<std::vector<float>> decodeToBinaural(const std::vector<std::vector<float>>& ambix, const Hrtf& hrtf);

}  // namespace diffray::spatial
