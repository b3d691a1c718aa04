#include "diffray/transport/tracer.h"

#include <cmath>

#include "diffray/core/error.h"
#include "diffray/core/parallel.h"

namespace diffray::transport {

using core::Vec3;

void TraceResult::merge(const TraceResult& o) {
  for (std::size_t i = 0; i < screens.size(); ++i) screens[i].merge(o.screens[i]);
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

struct PathState {
  Vec3 origin, dir;
  double energy;
  double tnear;
};

// Scatters a ray at an occluder (paper eq. 8–10). Returns false when the ray ends there.
bool scatterAtOccluder(const Occluder& occ, const Vec3& hit, double wavelength, core::ChunkSampler& sampler,
                       PathState& s, TraceResult& acc) {
  const geometry::Frame& f = occ.frame;
  const double x = f.localX(hit), y = f.localY(hit);
  const double alpha = s.dir.dot(f.ex), beta = s.dir.dot(f.ey), gamma = s.dir.dot(f.n);
  const wbsdf::WbsdfTable::Sample sx = occ.table_x->sample(x, sampler.next());
  const double xi_y = sampler.next();  // drawn even when unused, so dimensions stay aligned across rays
  double weight = sx.weight;
  double v_shift = 0.0;
  if (occ.table_y && weight != 0.0) {
    const wbsdf::WbsdfTable::Sample sy = occ.table_y->sample(y, xi_y);
    weight *= sy.weight;
    v_shift = sy.u_shift;
  }
  if (weight == 0.0) {  // t = 0 here: the opaque part of the occluder
    acc.absorbed += s.energy;
    return false;
  }
  s.energy *= weight;
  // u_o = u_i + u' (cycles per metre); direction cosines are λ·u.
  const double alpha_o = alpha + wavelength * sx.u_shift;
  const double beta_o = beta + wavelength * v_shift;
  const double gamma_sq = 1.0 - alpha_o * alpha_o - beta_o * beta_o;
  if (gamma_sq <= 0.0) {
    acc.evanescent += s.energy;
    return false;
  }
  double gamma_o = std::copysign(std::sqrt(gamma_sq), gamma);
  if (occ.reflect) gamma_o = -gamma_o;
  s.dir = alpha_o * f.ex + beta_o * f.ey + gamma_o * f.n;
  s.origin = hit;
  s.tnear = 1e-6 * (1.0 + hit.lpNorm<Eigen::Infinity>());
  return true;
}

}  // namespace

TraceResult trace(const Scene& scene, const CollimatedSource& source, const TraceOptions& options) {
  core::requirePositive("wavelength", source.wavelength_m);
  if (options.rays == 0) throw core::InputError("--rays", "must be > 0");
  const double lambda = source.wavelength_m;
  const Vec3 dir0 = source.dir.normalized();
  const double ray_energy = source.power() / static_cast<double>(options.rays);
  const geometry::Intersector& isect = scene.intersector();

  auto make = [&] {
    TraceResult r;
    for (const auto& s : scene.screens()) r.screens.emplace_back(s.bins());
    return r;
  };
  auto body = [&](TraceResult& acc, core::Rng& rng, std::uint64_t begin, std::uint64_t end) {
    // Quasi-random dimensions: source x, source y, then the first occluder's u' and v'.
    core::ChunkSampler sampler(rng, 4, options.qmc);
    for (std::uint64_t i = begin; i < end; ++i) {
      sampler.startRay(i - begin);
      PathState s;
      const double sx = (2.0 * sampler.next() - 1.0) * source.half_x_m;
      const double sy = (2.0 * sampler.next() - 1.0) * source.half_y_m;
      s.origin = source.frame.origin + sx * source.frame.ex + sy * source.frame.ey;
      s.dir = dir0;
      s.energy = ray_energy;
      s.tnear = 0.0;
      acc.emitted += ray_energy;
      ++acc.rays;
      bool alive = true;
      for (int bounce = 0; alive; ++bounce) {
        if (bounce == options.max_bounces) {
          acc.bounce_limit += s.energy;
          break;
        }
        geometry::Ray ray{s.origin, s.dir, s.tnear, 1e300};
        const geometry::Hit hit = isect.intersect(ray);
        ++acc.segments;
        if (!hit.valid()) {
          acc.escaped += s.energy;
          break;
        }
        const Scene::ObjectRef& obj = scene.object(hit.object);
        // Refine Embree's float distance on the object's plane, in double (design.md §1).
        const double t = obj.frame->planeDistance(s.origin, s.dir);
        const Vec3 p = s.origin + (std::isfinite(t) && t > 0 ? t : hit.t) * s.dir;
        switch (obj.kind) {
          case ObjectKind::Screen: {
            const receiver::Screen& scr = scene.screens()[obj.index];
            const int bin = scr.binOf(scr.frame.localX(p), scr.frame.localY(p));
            if (bin >= 0) acc.screens[obj.index].add(bin, s.energy);
            else acc.escaped += s.energy;  // clipped by a float round-off at the very edge
            alive = false;
            break;
          }
          case ObjectKind::Absorber:
            acc.on_absorbers += s.energy;
            alive = false;
            break;
          case ObjectKind::Occluder:
            alive = scatterAtOccluder(scene.occluders()[obj.index], p, lambda, sampler, s, acc);
            break;
        }
      }
    }
    for (auto& t : acc.screens) t.closeChunk();
  };
  auto progress = [&](std::uint64_t n) {
    if (options.on_progress) options.on_progress(n);
  };
  return core::deterministicReduce<TraceResult>(options.rays, options.chunk_rays, options.seed, make, body,
                                                progress);
}

}  // namespace diffray::transport
