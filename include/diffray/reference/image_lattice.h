#pragma once
// The exact specular response of a shoebox room by image sources (Allen & Berkley 1979), for the `shoebox-ism`
// and `specular-decay` validation cases: every image of an omnidirectional 1 W source in the rigid-walled
// box [0, Lx] × [0, Ly] × [0, Lz] up to a reflection order and/or a distance, with its delay and its
// energy per band, and the same sum binned into a band × time histogram.
//
// The images form a lattice, enumerated in closed form (no recursive mirroring). Along x, the image in
// cell n (the copy of the room [n·Lx, (n+1)·Lx]) sits at
//     x_n = n·Lx + x_s        for even n   (= +x_s + 2l·Lx, l = n/2),
//     x_n = (n+1)·Lx − x_s    for odd n    (= −x_s + 2l·Lx, l = (n+1)/2),
// and its path crosses the |n| planes between cell 0 and cell n: x = k·Lx for k = 1…n (n > 0) or
// k = n+1…0 (n < 0). A plane at an even multiple of Lx is an image of the wall x = 0 (x−), one at an odd
// multiple of the wall x = Lx (x+). Hence n > 0: ⌈n/2⌉ hits on x+ and ⌊n/2⌋ on x−; n < 0: ⌈|n|/2⌉ on
// x− and ⌊|n|/2⌋ on x+; the order is |nx| + |ny| + |nz|. Images of order ≤ N: (2N+1)(2N²+2N+3)/3.
//
// Energy of an image at distance d, per band: Π_walls β_w^{hits_w} · e^{−m d} / d² (the receivers'
// convention: 1 W gives 1/r² at r), β_w the specular energy reflection factor of wall w, (1 − α)(1 − s);
// delay d/c. Walls are ordered x−, x+, y−, y+, z− (floor), z+ (ceiling), as in room::Room::addBox.
//
// An ORACLE: it shares no code with the tracer, the room loader or the receivers. Invalid arguments throw
// core::InputError. Pure functions; thread-safe.
#include <array>
#include <limits>
#include <vector>

namespace diffray::reference {

/// "No limit" for max_order and max_distance_m (at most one of the two may be unlimited).
inline constexpr int kAnyOrder = std::numeric_limits<int>::max();
inline constexpr double kAnyDistance = std::numeric_limits<double>::infinity();

struct ImageArrival {
  double delay_s = 0.0;
  double distance_m = 0.0;
  std::array<int, 3> lattice{};      ///< cell indices (nx, ny, nz); (0, 0, 0) is the direct sound
  int order = 0;                     ///< |nx| + |ny| + |nz|
  std::array<int, 6> hits{};         ///< reflections on x−, x+, y−, y+, z−, z+
  std::array<double, 3> position_m{};  ///< the image source, in the room's frame
  std::vector<double> energy;        ///< per band
};

/// Everything shoeboxImages and shoeboxEnergyHistogram need besides the limits. `reflection_energy[w]`
/// and `air_m_per_m` have one entry per band (all the same length); β in [0, 1], m >= 0 in 1/m (energy);
/// source and receiver strictly inside the box and apart.
struct Shoebox {
  std::array<double, 3> dims_m{};
  std::array<double, 3> source_m{};
  std::array<double, 3> receiver_m{};
  std::array<std::vector<double>, 6> reflection_energy;
  std::vector<double> air_m_per_m;
  double c_m_s = 343.0;
};

/// Every image with order <= max_order AND distance <= max_distance_m, sorted by distance.
std::vector<ImageArrival> shoeboxImages(const Shoebox& box, int max_order, double max_distance_m);

/// The same sum binned into [band][bin], bin b holding the arrivals with b·bin_s <= d/c < (b+1)·bin_s, up
/// to length_s (ceil(length_s/bin_s) bins). The image set is cut at c·(bins·bin_s), so the histogram is
/// COMPLETE whatever the order when max_order is kAnyOrder: the exact specular decay of the room.
std::vector<std::vector<double>> shoeboxEnergyHistogram(const Shoebox& box, double bin_s, double length_s,
                                                        int max_order = kAnyOrder);

/// The same two with the box spelled out (dims, source, receiver, β per wall and band, m per band, c).
inline std::vector<ImageArrival> shoeboxImages(const std::array<double, 3>& dims_m,
                                               const std::array<double, 3>& source_m,
                                               const std::array<double, 3>& receiver_m,
                                               const std::array<std::vector<double>, 6>& reflection_energy,
                                               const std::vector<double>& air_m_per_m, double c_m_s,
                                               int max_order, double max_distance_m) {
  return shoeboxImages(Shoebox{dims_m, source_m, receiver_m, reflection_energy, air_m_per_m, c_m_s}, max_order,
                       max_distance_m);
}
inline std::vector<std::vector<double>> shoeboxEnergyHistogram(
    const std::array<double, 3>& dims_m, const std::array<double, 3>& source_m,
    const std::array<double, 3>& receiver_m, const std::array<std::vector<double>, 6>& reflection_energy,
    const std::vector<double>& air_m_per_m, double c_m_s, double bin_s, double length_s,
    int max_order = kAnyOrder) {
  return shoeboxEnergyHistogram(Shoebox{dims_m, source_m, receiver_m, reflection_energy, air_m_per_m, c_m_s},
                                bin_s, length_s, max_order);
}

}  // namespace diffray::reference
