#pragma once
// The WBSDF occluders of a room at run time (room/occluder.h): which triangle belongs to which occluder,
// and the scattering of a single-wavelength ray that meets one (paper eq. 8–10). A hit at
// local (x, y) with incident direction cosines (α, β, γ) draws shifts (u', v') from W_x(x,·) and W_y(y,·):
// openings and edges by the analytic edge kernel (wbsdf/edge_kernel.h, exact for any wavelength), slit
// arrays and gratings from a WbsdfTable built once for the shortest wavelength of the bands (W in u does not
// depend on λ; only the table's range does). The outgoing direction is (α + λu', β + λv', ±√(1 − …));
// an imaginary root is an evanescent wave and the ray ends. The signed weight W/p multiplies the ray's
// energy. Immutable once built; thread-safe.
#include <memory>
#include <vector>

#include "diffray/core/math.h"
#include "diffray/room/room.h"
#include "diffray/transport/opening_transmission.h"
#include "diffray/wbsdf/table.h"

namespace diffray::transport {

/// The energy factor of OccluderAxis::Faces for a ray arriving along d_in and leaving along d_out across an
/// edge whose open side lies along `open` (unit, in the occluder's plane, perpendicular to the edge), occluder
/// normal n: |1 ± cos((φ − φ0)/2)/cos((φ + φ0)/2)|² (+ rigid, − soft; 1 for Kirchhoff), angles in the plane
/// across the edge from its screen face (−open), capped at 4 (the grazing limit).
double facesFactor(room::OccluderAxis::Faces faces, const core::Vec3& open, const core::Vec3& n,
                   const core::Vec3& d_in, const core::Vec3& d_out);

class RoomOccluders {
 public:
  /// `shortest_wavelength_m` sets the range of the tables (slit arrays, gratings).
  RoomOccluders(const room::Room& room, double shortest_wavelength_m);

  bool empty() const { return occluders_.empty(); }
  /// The occluder whose opening or panel triangle `tri` is, or −1.
  int occluderOf(int tri) const { return tri < static_cast<int>(of_triangle_.size()) ? of_triangle_[tri] : -1; }
  /// Per triangle: 1 where an occluder sits (image sources must not pass there when diffraction is on).
  const std::vector<char>& triangleMask() const { return mask_; }

  struct Scatter {
    bool alive = false;      ///< false: evanescent, or t = 0 where the ray met the occluder
    bool evanescent = false;
    double weight = 0.0;     ///< signed factor on the ray's energy (reflectance of gratings not included)
    core::Vec3 dir{0, 0, 1};
  };
  /// Scatters a ray of wavelength `lambda_m` meeting occluder `k` at `p` with unit direction `dir`, from
  /// four uniforms in [0, 1).
  Scatter scatter(int k, const core::Vec3& p, const core::Vec3& dir, double lambda_m, const double xi[4]) const;

  struct PortalScatter {
    bool alive = false;
    bool evanescent = false;
    core::Vec3 dir{0, 0, 1};
  };
  /// The portal scattering of a ray that carries n bands at once (RoomTraceOptions::portal), at wavelengths
  /// lambda_m[0 … n): one outgoing direction, drawn from the law of band `pick` (the caller picks it
  /// uniformly: the draw is then from the mixture of the bands' laws), and per band i the factor
  /// weight[i] = f_i/((1/n)Σ_j q_j) on its energy (one-sample multiple importance sampling, balance heuristic):
  /// f_i the band's target density, q_j the bands' proposal densities, so that every band's expectation is
  /// that of its own law. Opening axes draw from the opening's far-field pattern |T(u)|²/∫|t|²
  /// (wbsdf/far_field.h) instead of W(x,·): the product of W's two marginals, exact in both (the energy through
  /// each point, the pattern of the whole opening), positive, without W's correlation of position and
  /// direction (its near-field fringes: the caller's next-event estimate keeps those). Both marginals hold
  /// over the whole line; the propagating range cuts the two differently (W's propagating part depends on
  /// the hit point, the pattern's does not), a difference of second order in the cut. An occluder's `faces`
  /// factor (rigid or soft edges) multiplies the draw as in scatter(), with the nearer edge. Edge axes from the edge kernel (signed), uniform axes pass. For occluders that support
  /// next-event estimation (the caller's next-event estimate serves the first flight with the exact W).
  PortalScatter scatterPortal(int k, const core::Vec3& p, const core::Vec3& dir, const double* lambda_m, int n,
                              int pick, const double xi[4], double* weight) const;

  /// Next-event estimation (a conditional expectation over the WBSDF draw): the expected score of a listener
  /// sphere, E[weight · faces · chordWeight/crossSection · 1(the scattered ray crosses the sphere)], per unit
  /// of the ray's energy, for a ray of wavelength λ meeting occluder k at p along `dir` — what the sphere
  /// would gain on average from the scattered ray's next segment, computed by quadrature over the directions
  /// that cross it instead of by one random ray. The x shift is integrated; for two edge axes (a door) the
  /// y shift is drawn from the uniforms `xi` (its weight multiplies the result), so the estimate is exact
  /// in expectation over xi. Only for openings and edges (nextEventSupported), not gratings or slit arrays;
  /// 0 when the sphere lies on the incident side of the plane; NaN when the kernel swings through more than
  /// 64 periods across the sphere (far from the edges: it averages out, and the ray itself scores as well).
  /// Visibility between p and the sphere is the caller's business.
  double expectedSphereScore(int k, const core::Vec3& p, const core::Vec3& dir, double lambda_m,
                             const core::Vec3& centre, double radius_m, const double xi[2]) const;
  bool nextEventSupported(int k) const;

  /// Whether occluder k returns the energy its opening does not carry: an opening (each axis an opening or
  /// uniform, Kirchhoff faces, not a grating) in a wall that reflects (surround(k) not zero). Kirchhoff's
  /// opening passes the part τ of what arrives that its far-field pattern sends into propagating directions
  /// (OpeningTransmission); in a black screen the rest is absorbed, in a wall that reflects it comes back.
  bool returnsEnergy(int k) const { return occluders_[k].returns; }
  /// The reflectance 1 − α per band of the wall around occluder k (surroundReflectance).
  const core::BandArray& surround(int k) const { return occluders_[k].surround; }
  /// τ̄ of band b (OpeningTransmission::at) for a ray along unit `dir` at occluder k; only where returnsEnergy.
  double transmission(int k, int band, const core::Vec3& dir) const {
    const Entry& e = occluders_[k];
    return e.tau.at(band, dir.dot(e.spec.ex), dir.dot(e.spec.ey));
  }

  const room::Occluder& occluder(int k) const { return occluders_[k].spec; }
  int size() const { return static_cast<int>(occluders_.size()); }

 private:
  struct Axis {
    room::OccluderAxis spec;
    std::shared_ptr<const wbsdf::WbsdfTable> table;  ///< Slits, Grating
  };
  struct Entry {
    room::Occluder spec;
    Axis x, y;
    core::BandArray surround = core::bandFill(0.0);
    bool returns = false;
    OpeningTransmission tau;  ///< built where `returns`
  };
  /// The reflectance 1 − α per band of the wall around opening `o`, averaged over its diffracting edges
  /// (occluder_surround.cpp): at the middle of each edge, the nearest surface within 0.25 m that is no
  /// occluder's and no opening, found along the occluder's plane from just inside the opening outward (a
  /// thick wall's reveal), else toward the plane from just beyond the edge (a thin wall). Zero for
  /// occluders that are not openings with Kirchhoff faces, and where no surface is found (an opening in
  /// free space).
  static core::BandArray surroundReflectance(const room::Room& room, const room::Occluder& o,
                                             const std::vector<int>& of_triangle);
  /// Shift u' (cycles per metre) and its weight along one axis at local coordinate c, for incident direction
  /// cosine `alpha` along the axis, drawn (edge kernels) where |alpha + λu'| < alpha_max. `open_sign`: ±1
  /// the direction along the axis from the nearer diffracting edge into the opening, 0 if none.
  static void sampleAxis(const Axis& a, double c, double lambda_m, double alpha, double alpha_max,
                         const double* xi, double& u, double& w, double& open_sign);
  /// The edge kernel's scale along an axis at local coordinate c: 4d (d the distance to the nearer
  /// diffracting edge) and the sign of the direction from that edge into the opening.
  static void edgeDistance(const Axis& a, double c, double& four_d, double& open_sign);
  struct AxisLaw;  ///< one axis's law of the outgoing direction cosine for scatterPortal (occluder_portal.cpp)
  static AxisLaw axisLaw(const Axis& a, double coord, double c, double c_max);
  std::vector<Entry> occluders_;
  std::vector<int> of_triangle_;
  std::vector<char> mask_;
};

}  // namespace diffray::transport
