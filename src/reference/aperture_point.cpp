// 3D Rayleigh–Sommerfeld (first kind) reference for a point source behind rectangular openings, by
// composite Gauss–Legendre quadrature (Goodman, "Introduction to Fourier Optics", ch. 3; the header has the formula,
// frame and grid rules).
#include "diffray/reference/aperture_point.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "diffray/core/error.h"
#include "diffray/core/parallel.h"
#include "diffray/reference/band_grid.h"
#include "diffray/reference/quadrature.h"

namespace diffray::reference {
namespace {

using Complex = std::complex<double>;

constexpr double kPi = 3.14159265358979323846;
constexpr double kPhasePerPanelRad = 4.0 * kPi;  // max change of k(r_s + r) across one panel
constexpr double kFootFraction = 1.0;            // panel length / distance to the nearest foot point
constexpr double kMaxNodes = 5e7;
constexpr int kReseedSteps = 256;  // phase recurrence re-seeded this often in the band average

// One quadrature node: the integrand is e^{−ikL}·(a0 + ik·a1), with L = r_s + r and
// a1 = w·z_P/(2π r_s r²), a0 = a1/r (w the product Gauss weight × panel Jacobian).
struct Node {
  double path_m;
  double a0;
  double a1;
};

// d/√(d² + h²): the component along one axis of the unit vector from a foot point at height h.
double slope(double d_m, double height_m) { return d_m / std::hypot(d_m, height_m); }

// Distance from `foot_m` to the interval [a_m, b_m].
double gap(double a_m, double b_m, double foot_m) { return std::max({0.0, a_m - foot_m, foot_m - b_m}); }

// Panel breakpoints on [begin, end] along one axis for a source foot point (foot_s, height_s) and a
// receiver foot point (foot_r, height_r): each panel [a, b] keeps k·sup|∂L/∂x|·(b − a) <= kPhasePerPanelRad,
// with sup|∂L/∂x| <= max(σ_s(b)⁺ + σ_r(b)⁺, σ_s(a)⁻ + σ_r(a)⁻) (σ = slope, monotone in x; offsets along the
// other axis only shrink it), and (b − a) <= kFootFraction·(distance to either foot point). Every cap is
// evaluated on the trial panel, which contains the accepted one, so the accepted panel satisfies both.
std::vector<double> panelBreaks(double begin_m, double end_m, double foot_s_m, double height_s_m,
                                double foot_r_m, double height_r_m, double k_per_m) {
  std::vector<double> breaks{begin_m};
  double x_m = begin_m;
  double previous_m = end_m - begin_m;
  while (x_m < end_m) {
    double h_m = std::min(end_m - x_m, 2.0 * previous_m);
    const double b_m = x_m + h_m;
    const double sup = std::max(slope(b_m - foot_s_m, height_s_m), 0.0) +
                       std::max(slope(b_m - foot_r_m, height_r_m), 0.0);
    const double inf = std::min(slope(x_m - foot_s_m, height_s_m), 0.0) +
                       std::min(slope(x_m - foot_r_m, height_r_m), 0.0);
    const double gradient = std::max(sup, -inf);
    if (gradient > 0.0) h_m = std::min(h_m, kPhasePerPanelRad / (k_per_m * gradient));
    const double foot_m = std::min(std::hypot(gap(x_m, b_m, foot_s_m), height_s_m),
                                   std::hypot(gap(x_m, b_m, foot_r_m), height_r_m));
    h_m = std::min(h_m, kFootFraction * foot_m);
    x_m = (end_m - (x_m + h_m) <= 1e-12 * (end_m - begin_m)) ? end_m : x_m + h_m;
    breaks.push_back(x_m);
    previous_m = h_m;
    if (static_cast<double>(breaks.size()) * GaussRule::kNodes * GaussRule::kNodes > kMaxNodes)
      throw core::InputError("aperturePointSource: openings",
                             "too large for direct quadrature at this wavelength (more than 5e7 nodes)");
  }
  return breaks;
}

// Appends the nodes of one opening for one (possibly image) source.
void appendNodes(const ApertureRect& rect, const CartesianPoint& source, const CartesianPoint& receiver,
                 double k_max_per_m, std::vector<Node>& nodes) {
  const double height_s_m = -source.z_m, height_r_m = receiver.z_m;
  const std::vector<double> xs =
      panelBreaks(rect.x0_m, rect.x1_m, source.x_m, height_s_m, receiver.x_m, height_r_m, k_max_per_m);
  const std::vector<double> ys =
      panelBreaks(rect.y0_m, rect.y1_m, source.y_m, height_s_m, receiver.y_m, height_r_m, k_max_per_m);
  const GaussRule& rule = gaussRule16();
  constexpr int n = GaussRule::kNodes;
  const double count = static_cast<double>(nodes.size()) +
                       static_cast<double>(xs.size() - 1) * static_cast<double>(ys.size() - 1) * n * n;
  if (count > kMaxNodes)
    throw core::InputError("aperturePointSource: openings",
                           "too large for direct quadrature at this wavelength (more than 5e7 nodes)");
  nodes.reserve(static_cast<std::size_t>(count));
  // Per-axis nodes and weights first (x and y parts of both distances), then the tensor product.
  auto axisNodes = [&](const std::vector<double>& breaks, std::vector<double>& at, std::vector<double>& w) {
    for (std::size_t p = 0; p + 1 < breaks.size(); ++p) {
      const double mid = 0.5 * (breaks[p] + breaks[p + 1]), half = 0.5 * (breaks[p + 1] - breaks[p]);
      for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) {
        at.push_back(mid + half * rule.nodes[i]);
        w.push_back(half * rule.weights[i]);
      }
    }
  };
  std::vector<double> x_at, x_w, y_at, y_w;
  axisNodes(xs, x_at, x_w);
  axisNodes(ys, y_at, y_w);
  const double factor = height_r_m / (2.0 * kPi);
  for (std::size_t i = 0; i < x_at.size(); ++i) {
    const double dxs = x_at[i] - source.x_m, dxr = x_at[i] - receiver.x_m;
    const double xs2 = dxs * dxs + height_s_m * height_s_m, xr2 = dxr * dxr + height_r_m * height_r_m;
    for (std::size_t j = 0; j < y_at.size(); ++j) {
      const double dys = y_at[j] - source.y_m, dyr = y_at[j] - receiver.y_m;
      const double r_s = std::sqrt(xs2 + dys * dys), r = std::sqrt(xr2 + dyr * dyr);
      const double a1 = factor * x_w[i] * y_w[j] / (r_s * r * r);
      nodes.push_back({r_s + r, a1 / r, a1});
    }
  }
}

void requirePoint(const std::string& where, const CartesianPoint& p) {
  core::requireFinite(where + ".x_m", p.x_m);
  core::requireFinite(where + ".y_m", p.y_m);
  core::requireFinite(where + ".z_m", p.z_m);
}

bool overlap(const ApertureRect& a, const ApertureRect& b) {
  return a.x0_m < b.x1_m && b.x0_m < a.x1_m && a.y0_m < b.y1_m && b.y0_m < a.y1_m;
}

// Validates everything and returns the quadrature nodes for wavenumbers up to k_max.
std::vector<Node> buildNodes(const std::string& where, const ApertureScreen& screen,
                             const CartesianPoint& source, const CartesianPoint& receiver,
                             double k_max_per_m) {
  requirePoint(where + ": source", source);
  requirePoint(where + ": receiver", receiver);
  if (!(source.z_m < 0.0))
    throw core::InputError(where + ": source.z_m", "the source must lie in front of the screen (z < 0), got " +
                                                       std::to_string(source.z_m));
  if (!(receiver.z_m > 0.0))
    throw core::InputError(where + ": receiver.z_m", "the receiver must lie behind the screen (z > 0), got " +
                                                         std::to_string(receiver.z_m));
  if (screen.openings.empty())
    throw core::InputError(where + ": openings", "no openings: the screen is closed and the field is zero");
  for (std::size_t i = 0; i < screen.openings.size(); ++i) {
    const ApertureRect& rect = screen.openings[i];
    const std::string name = where + ": opening " + std::to_string(i);
    for (double v : {rect.x0_m, rect.x1_m, rect.y0_m, rect.y1_m}) core::requireFinite(name, v);
    if (!(rect.x0_m < rect.x1_m) || !(rect.y0_m < rect.y1_m))
      throw core::InputError(name, "must have x0 < x1 and y0 < y1 (empty or reversed rectangle)");
    for (std::size_t j = 0; j < i; ++j)
      if (overlap(rect, screen.openings[j]))
        throw core::InputError(name, "overlaps opening " + std::to_string(j));
  }
  if (screen.floor_y_m) {
    const double floor_m = *screen.floor_y_m;
    core::requireFinite(where + ": floor_y_m", floor_m);
    if (source.y_m < floor_m || receiver.y_m < floor_m)
      throw core::InputError(where + ": floor_y_m", "source and receiver must lie at y >= floor_y_m");
    for (const ApertureRect& rect : screen.openings)
      if (rect.y0_m < floor_m)
        throw core::InputError(where + ": floor_y_m", "every opening must lie at y >= floor_y_m");
  }
  std::vector<Node> nodes;
  for (const ApertureRect& rect : screen.openings) appendNodes(rect, source, receiver, k_max_per_m, nodes);
  if (screen.floor_y_m) {
    // Unfolded: the source through the mirrored openings, and its image through all of them.
    const double floor_m = *screen.floor_y_m;
    const CartesianPoint image{source.x_m, 2.0 * floor_m - source.y_m, source.z_m};
    for (const ApertureRect& rect : screen.openings) {
      const ApertureRect mirrored{rect.x0_m, rect.x1_m, 2.0 * floor_m - rect.y1_m, 2.0 * floor_m - rect.y0_m};
      appendNodes(mirrored, source, receiver, k_max_per_m, nodes);
      appendNodes(rect, image, receiver, k_max_per_m, nodes);
      appendNodes(mirrored, image, receiver, k_max_per_m, nodes);
    }
  }
  return nodes;
}

double distance(const CartesianPoint& a, const CartesianPoint& b) {
  return std::hypot(a.x_m - b.x_m, a.y_m - b.y_m, a.z_m - b.z_m);
}

// Σ e^{−ikL}(a0 + ik·a1) for one wavenumber.
Complex sumNodes(const std::vector<Node>& nodes, double k_per_m) {
  double s0_re = 0.0, s0_im = 0.0, s1_re = 0.0, s1_im = 0.0;
  for (const Node& node : nodes) {
    const double phase = k_per_m * node.path_m;
    const double c = std::cos(phase), s = -std::sin(phase);
    s0_re += c * node.a0;
    s0_im += s * node.a0;
    s1_re += c * node.a1;
    s1_im += s * node.a1;
  }
  return Complex(s0_re, s0_im) + Complex(0.0, k_per_m) * Complex(s1_re, s1_im);
}

}  // namespace

Complex aperturePointSource(double wavelength_m, const ApertureScreen& screen, const CartesianPoint& source,
                            const CartesianPoint& receiver) {
  core::requirePositive("aperturePointSource: wavelength_m", wavelength_m);
  const double k_per_m = 2.0 * kPi / wavelength_m;
  return sumNodes(buildNodes("aperturePointSource", screen, source, receiver, k_per_m), k_per_m);
}

double apertureLevelDb(double wavelength_m, const ApertureScreen& screen, const CartesianPoint& source,
                       const CartesianPoint& receiver) {
  const Complex u = aperturePointSource(wavelength_m, screen, source, receiver);
  return 20.0 * std::log10(std::abs(u) * distance(source, receiver));
}

double apertureBandLevelDb(double f_lo_hz, double f_hi_hz, int points, double sound_speed_m_s,
                           const ApertureScreen& screen, const CartesianPoint& source,
                           const CartesianPoint& receiver) {
  core::requirePositive("apertureBandLevelDb: sound_speed_m_s", sound_speed_m_s);
  const std::vector<double> grid_hz = bandGridHz("apertureBandLevelDb", f_lo_hz, f_hi_hz, points);
  const double k_scale = 2.0 * kPi / sound_speed_m_s;
  const std::vector<Node> nodes =
      buildNodes("apertureBandLevelDb", screen, source, receiver, k_scale * grid_hz.back());
  const std::size_t m = grid_hz.size();
  const double dk = m > 1 ? k_scale * (grid_hz[1] - grid_hz[0]) : 0.0;
  // Per-frequency sums S0, S1 (re, im interleaved), accumulated node by node with the phase factor
  // e^{−ik_j L} stepped by e^{−iΔk·L}; chunks of nodes reduce in a fixed order (core/parallel.h).
  struct Sums {
    std::vector<double> s;  // [4·j + 0..3] = S0 re, S0 im, S1 re, S1 im
    void merge(const Sums& other) {
      for (std::size_t i = 0; i < s.size(); ++i) s[i] += other.s[i];
    }
  };
  const Sums sums = core::deterministicReduce<Sums>(
      nodes.size(), 4096, 0, [&] { return Sums{std::vector<double>(4 * m, 0.0)}; },
      [&](Sums& acc, core::Rng&, std::uint64_t begin, std::uint64_t end) {
        for (std::uint64_t i = begin; i < end; ++i) {
          const Node& node = nodes[i];
          const double step_re = std::cos(dk * node.path_m), step_im = -std::sin(dk * node.path_m);
          double p_re = 0.0, p_im = 0.0;
          for (std::size_t j = 0; j < m; ++j) {
            if (j % kReseedSteps == 0) {
              const double phase = k_scale * grid_hz[j] * node.path_m;
              p_re = std::cos(phase);
              p_im = -std::sin(phase);
            }
            double* s = &acc.s[4 * j];
            s[0] += p_re * node.a0;
            s[1] += p_im * node.a0;
            s[2] += p_re * node.a1;
            s[3] += p_im * node.a1;
            const double next_re = p_re * step_re - p_im * step_im;
            p_im = p_re * step_im + p_im * step_re;
            p_re = next_re;
          }
        }
      },
      [](std::uint64_t) {});
  const double r_m = distance(source, receiver);
  double energy = 0.0;
  for (std::size_t j = 0; j < m; ++j) {
    const double k_per_m = k_scale * grid_hz[j];
    const Complex u = Complex(sums.s[4 * j], sums.s[4 * j + 1]) +
                      Complex(0.0, k_per_m) * Complex(sums.s[4 * j + 2], sums.s[4 * j + 3]);
    energy += std::norm(u) * r_m * r_m;
  }
  return 10.0 * std::log10(energy / static_cast<double>(m));
}

}  // namespace diffray::reference
