#include "diffray/transport/tracer.h"

#include <cmath>
#include <limits>

#include "diffray/core/error.h"
#include "diffray/core/parallel.h"

namespace diffray::transport {

using core::Vec3;

void TraceResult::merge(const TraceResult& o) {
  for (std::size_t i = 0; i < screens.size(); ++i) screens[i].merge(o.screens[i]);
  for (std::size_t i = 0; i < spheres.size(); ++i) spheres[i].merge(o.spheres[i]);
  far_field.merge(o.far_field);
  emitted += o.emitted;
  absorbed += o.absorbed;
  evanescent += o.evanescent;
  escaped += o.escaped;
  on_absorbers += o.on_absorbers;
  bounce_limit += o.bounce_limit;
  rays += o.rays;
  segments += o.segments;
}

namespace {

// The hot loop works on plain doubles: a few dot products per event, with no temporaries.
inline double dot(const double* a, const Vec3& b) { return a[0] * b.x() + a[1] * b.y() + a[2] * b.z(); }

// Quasi-random dimensions of a path (core::ChunkSampler): each source coordinate is paired with the
// direction drawn from it, x with u' and y with v'. The pair (x, u') decides the 2D problems, so it gets
// the R2 generators (1/ρ, 1/ρ², ρ the plastic number), the best-known 2D Kronecker lattice; y, v' and λ
// get φ − 1, √2 − 1 and √3 − 1, independent of those over the rationals so the 5D set stays uniform.
constexpr int kDimX = 0, kDimU = 1, kDimY = 2, kDimV = 3, kDimLambda = 4, kDimFree = 5;
constexpr double kGenerators[kDimFree] = {0.7548776662466927, 0.5698402909980532, 0.6180339887498949,
                                          0.4142135623730950, 0.7320508075688772};

struct PathState {
  double o[3], d[3];    ///< origin and unit direction (world, metres), double precision
  double energy;        ///< signed energy
  double lambda;        ///< wavelength (m) this ray carries
  double tnear;
  std::uint64_t index;  ///< ray index within its chunk (its quasi-random point)
  int dim;              ///< next uniform dimension of this ray
};

// Scatters a ray at an occluder (paper eq. 8–10: u_o = u_i + u', the sign of W in the energy).
// `p` is the hit point in double. Returns false when the ray ends there.
bool scatterAtOccluder(const Occluder& occ, const Scene::ObjectRef& obj, const double* p,
                       core::ChunkSampler& sampler, PathState& s, TraceResult& acc) {
  const geometry::Frame& f = obj.frame;
  const double x = dot(p, f.ex) - obj.origin_x, y = dot(p, f.ey) - obj.origin_y;
  // The first scattering uses the quasi-random dimensions paired with the source position (kDimU,
  // kDimV); later ones draw fresh uniforms.
  const bool first = s.dim == kDimFree;
  const double xi_x = first ? sampler.at(s.index, kDimU) : sampler.next(s.index, s.dim);
  const double xi_y = first ? sampler.at(s.index, kDimV) : sampler.next(s.index, s.dim);
  if (first) s.dim = kDimFree + 1;
  double weight = 0.0;
  const ScatterFate fate = transport::scatterAtOccluder(occ, f, x, y, s.lambda, xi_x, xi_y, s.d, weight);
  if (fate == ScatterFate::Absorbed) {  // t = 0 here: the opaque part of the occluder
    acc.absorbed += s.energy;
    return false;
  }
  s.energy *= weight;
  if (fate == ScatterFate::Evanescent) {
    acc.evanescent += s.energy;
    return false;
  }
  double extent = 1.0;
  for (int c = 0; c < 3; ++c) {
    s.o[c] = p[c];
    extent = std::max(extent, std::abs(p[c]));
  }
  s.tnear = 1e-6 * extent;  // clears the occluder's own plane in Embree's float arithmetic
  return true;
}

// Deposits the ray's energy in every sphere its segment [tnear, t_end) passes through, weighted by the
// chord inside (receiver/sphere.h: a track-length estimator). Out of line: most scenes have no sphere, and
// tallySpheres (below) then costs one inlined test instead of a call.
[[gnu::noinline]] void tallyEverySphere(const Scene& scene, const PathState& s, double t_end, TraceResult& acc) {
  const auto& spheres = scene.spheres();
  for (std::size_t i = 0; i < spheres.size(); ++i) {
    const double chord = spheres[i].chordLength(s.o, s.d, s.tnear, t_end);
    if (chord > 0.0) acc.spheres[i].add(0, s.energy * spheres[i].chordWeight(chord));
  }
}
inline void tallySpheres(const Scene& scene, const PathState& s, double t_end, TraceResult& acc) {
  if (!scene.spheres().empty()) tallyEverySphere(scene, s, t_end, acc);
}

// What happens to a ray at its next hit; returns whether it goes on.
bool followHit(const Scene& scene, int object, float t_embree, core::ChunkSampler& sampler, PathState& s,
               TraceResult& acc) {
  ++acc.segments;
  if (object < 0) {
    tallySpheres(scene, s, std::numeric_limits<double>::infinity(), acc);
    acc.escaped += s.energy;
    if (const FarField* ff = scene.farField()) {
      const double alpha = dot(s.d, ff->ex);
      const double f = (alpha - ff->alpha_lo) / (ff->alpha_hi - ff->alpha_lo);
      if (f >= 0.0 && f < 1.0) acc.far_field.add(std::min(static_cast<int>(f * ff->bins), ff->bins - 1), s.energy);
    }
    return false;
  }
  const Scene::ObjectRef& obj = scene.object(object);
  // Refine Embree's float distance on the object's plane, in double (a WBSDF is indexed at micron scale).
  const double dn = dot(s.d, obj.frame.n);
  double t = (obj.origin_n - dot(s.o, obj.frame.n)) / dn;
  if (!(std::isfinite(t) && t > 0)) t = t_embree;
  tallySpheres(scene, s, t, acc);
  const double p[3] = {s.o[0] + t * s.d[0], s.o[1] + t * s.d[1], s.o[2] + t * s.d[2]};
  switch (obj.kind) {
    case ObjectKind::Screen: {
      const receiver::Screen& scr = scene.screens()[obj.index];
      const int bin = scr.binOf(dot(p, obj.frame.ex) - obj.origin_x, dot(p, obj.frame.ey) - obj.origin_y);
      if (bin >= 0)
        acc.screens[obj.index].add(bin, scr.intensity ? s.energy / std::abs(dn) : s.energy);
      else
        acc.escaped += s.energy;  // clipped by a float round-off at the very edge
      return false;
    }
    case ObjectKind::Absorber:
      acc.on_absorbers += s.energy;
      return false;
    case ObjectKind::Occluder:
      return scatterAtOccluder(scene.occluders()[obj.index], obj, p, sampler, s, acc);
  }
  return false;
}

}  // namespace

ScatterFate scatterAtOccluder(const Occluder& occ, const geometry::Frame& f, double x_m, double y_m,
                              double wavelength_m, double xi_x, double xi_y, double* dir, double& weight,
                              bool uniform_shifts) {
  const double alpha = dot(dir, f.ex), beta = dot(dir, f.ey), gamma = dot(dir, f.n);
  const wbsdf::WbsdfTable::Sample sx =
      uniform_shifts ? occ.table_x->sampleUniform(x_m, xi_x) : occ.table_x->sample(x_m, xi_x);
  weight = sx.weight;
  double v_shift = 0.0;
  if (occ.table_y && weight != 0.0) {
    const wbsdf::WbsdfTable::Sample sy =
        uniform_shifts ? occ.table_y->sampleUniform(y_m, xi_y) : occ.table_y->sample(y_m, xi_y);
    weight *= sy.weight;
    v_shift = sy.u_shift;
  }
  if (weight == 0.0) return ScatterFate::Absorbed;
  // Direction cosines are λ·u (Cuypers et al. 2012, eq. 8–10); an imaginary γ is an evanescent wave: the ray ends.
  double alpha_o = alpha + wavelength_m * sx.u_shift;
  double beta_o = beta + wavelength_m * v_shift;
  if (occ.focal_length_m > 0.0) {  // a thin lens: the sheared WDF (scene.h, Occluder::focal_length_m)
    alpha_o -= x_m / occ.focal_length_m;
    beta_o -= y_m / occ.focal_length_m;
  }
  const double gamma_sq = 1.0 - alpha_o * alpha_o - beta_o * beta_o;
  if (gamma_sq <= 0.0) return ScatterFate::Evanescent;
  double gamma_o = std::copysign(std::sqrt(gamma_sq), gamma);
  if (occ.reflect) gamma_o = -gamma_o;  // paper eq. 9 (eq:reflection): the mirrored outgoing wave
  for (int c = 0; c < 3; ++c) dir[c] = alpha_o * f.ex[c] + beta_o * f.ey[c] + gamma_o * f.n[c];
  return ScatterFate::Continue;
}

TraceResult trace(const Scene& scene, const CollimatedSource& source, const TraceOptions& options) {
  core::requirePositive("wavelength", source.wavelength_m);
  core::requireFinite("maximum wavelength", source.wavelength_max_m);
  if (options.rays == 0) throw core::InputError("--rays", "must be > 0");
  // Frequencies uniform between c/λ_max and c/λ_min, i.e. 1/λ uniform.
  const double inv_lambda_hi = 1.0 / source.wavelength_m;
  const double inv_lambda_lo =
      source.wavelength_max_m > source.wavelength_m ? 1.0 / source.wavelength_max_m : inv_lambda_hi;
  const Vec3 dir0 = source.dir.normalized();
  const double ray_energy = source.power() / static_cast<double>(options.rays);
  const geometry::Intersector& isect = scene.intersector();

  auto make = [&] {
    TraceResult r;
    for (const auto& s : scene.screens()) r.screens.emplace_back(s.bins());
    r.spheres.assign(scene.spheres().size(), receiver::ScreenTally(1));
    r.far_field = receiver::ScreenTally(scene.farField() ? scene.farField()->bins : 0);
    return r;
  };
  // Rays travel in packets (Embree traces a packet at once); each keeps its own state.
  constexpr int kPacket = geometry::RayPacket::kSize;
  auto body = [&](TraceResult& acc, core::Rng& rng, std::uint64_t begin, std::uint64_t end) {
    core::ChunkSampler sampler(rng, kGenerators, kDimFree, options.qmc);
    PathState s[kPacket]{};  // lanes past the chunk's end are copied into the packet too (inactive)
    geometry::RayPacket packet;
    geometry::HitPacket hits;
    for (std::uint64_t first = begin; first < end; first += kPacket) {
      int alive = 0;
      for (int k = 0; k < kPacket; ++k) {
        packet.active[k] = first + k < end ? -1 : 0;
        if (!packet.active[k]) continue;
        ++alive;
        PathState& st = s[k];
        st.index = first + k - begin;
        st.dim = kDimFree;
        const double sx = (2.0 * sampler.at(st.index, kDimX) - 1.0) * source.half_x_m;
        const double sy = (2.0 * sampler.at(st.index, kDimY) - 1.0) * source.half_y_m;
        st.lambda = inv_lambda_lo == inv_lambda_hi
                        ? source.wavelength_m
                        : 1.0 / (inv_lambda_lo + sampler.at(st.index, kDimLambda) * (inv_lambda_hi - inv_lambda_lo));
        for (int c = 0; c < 3; ++c) {
          st.o[c] = source.frame.origin[c] + sx * source.frame.ex[c] + sy * source.frame.ey[c];
          st.d[c] = dir0[c];
        }
        st.energy = ray_energy;
        st.tnear = 0.0;
        acc.emitted += ray_energy;
        ++acc.rays;
      }
      for (int bounce = 0; alive > 0; ++bounce) {
        if (bounce == options.max_bounces) {
          for (int k = 0; k < kPacket; ++k)
            if (packet.active[k]) acc.bounce_limit += s[k].energy;
          break;
        }
        for (int k = 0; k < kPacket; ++k) {
          packet.org_x[k] = static_cast<float>(s[k].o[0]);
          packet.org_y[k] = static_cast<float>(s[k].o[1]);
          packet.org_z[k] = static_cast<float>(s[k].o[2]);
          packet.dir_x[k] = static_cast<float>(s[k].d[0]);
          packet.dir_y[k] = static_cast<float>(s[k].d[1]);
          packet.dir_z[k] = static_cast<float>(s[k].d[2]);
          packet.tnear[k] = static_cast<float>(s[k].tnear);
        }
        isect.intersectPacket(packet, hits);
        for (int k = 0; k < kPacket; ++k) {
          if (!packet.active[k]) continue;
          if (!followHit(scene, hits.object[k], hits.t[k], sampler, s[k], acc)) {
            packet.active[k] = 0;
            --alive;
          }
        }
      }
    }
    for (auto& t : acc.screens) t.closeChunk();
    for (auto& t : acc.spheres) t.closeChunk();
    acc.far_field.closeChunk();
  };
  return core::deterministicReduce<TraceResult>(options.rays, options.chunk_rays, options.seed, make, body,
                                                core::reportProgressTo(options.on_progress));
}

}  // namespace diffray::transport
