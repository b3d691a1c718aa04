#pragma once
// The reference module's own 16-point Gauss–Legendre rule (Newton iteration on P_16), so the oracles share
// no quadrature code with the ray tracer. Thread-safe (initialised once).
#include <array>

namespace diffray::reference {

struct GaussRule {
  static constexpr int kNodes = 16;
  std::array<double, kNodes> nodes{};
  std::array<double, kNodes> weights{};
};

const GaussRule& gaussRule16();

}  // namespace diffray::reference
