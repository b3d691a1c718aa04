#pragma once
// The parts of the field the BTM references of rigid obstacles return (btm_plate.h, btm_box.h,
// btm_spectrum.h): a unit point source's field at a receiver, e^{−ikR}/R in free field, time factor e^{+iωt}.
// Plain data; thread-safe to copy.
#include <complex>

namespace diffray::reference {

/// The field at a receiver split into its geometric and edge-diffracted parts.
struct BtmField {
  std::complex<double> direct{0.0, 0.0};        ///< e^{−ikR}/R where the segment misses the obstacle, else 0
  std::complex<double> specular{0.0, 0.0};      ///< the specular images whose reflection point is on the obstacle
  std::complex<double> diffracted{0.0, 0.0};    ///< Σ over the edges of the first-order BTM term
  std::complex<double> second_order{0.0, 0.0};  ///< Σ over ordered edge pairs of the edge-to-edge term (0 at order 1)
  std::complex<double> total() const { return direct + specular + diffracted + second_order; }
};

}  // namespace diffray::reference
