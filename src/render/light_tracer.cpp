#include "diffray/render/light_tracer.h"


#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "diffray/color/cie1931.h"
#include "diffray/color/wavelength.h"
#include "diffray/core/error.h"
#include "diffray/core/memory.h"
#include "diffray/core/parallel.h"
#include "diffray/transport/tracer.h"

namespace diffray::render {

void RenderResult::merge(const RenderResult& o) {
  for (std::size_t i = 0; i < xyz.size(); ++i) xyz[i] += o.xyz[i];
  radiance.merge(o.radiance);
  emitted += o.emitted;
  on_diffuse += o.on_diffuse;
  absorbed_occluders += o.absorbed_occluders;
  absorbed_diffuse += o.absorbed_diffuse;
  evanescent += o.evanescent;
  escaped += o.escaped;
  bounce_limit += o.bounce_limit;
  scored_positive += o.scored_positive;
  scored_negative += o.scored_negative;
  photons += o.photons;
  camera_scores += o.camera_scores;
}

double RenderResult::negativeScoreFraction() const {
  const double all = scored_positive + scored_negative;
  return all > 0 ? scored_negative / all : 0.0;
}

namespace {

using transport::ObjectKind;

// A photon in flight: position, unit direction, signed energy, wavelength.
struct Photon {
  Vec3 o, d;
  double energy = 0.0;
  double lambda_nm = 550.0;
  double tnear = 0.0;
  int diffuse_bounces = 0;
};

// A unit vector with pdf cosθ/π about `n` (Malley's method).
Vec3 cosineDirection(const Vec3& n, double u1, double u2) {
  const Vec3 t = (std::abs(n.x()) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0)).cross(n).normalized();
  const Vec3 b = n.cross(t);
  const double r = std::sqrt(u1), phi = core::kTwoPi * u2;
  return r * std::cos(phi) * t + r * std::sin(phi) * b + std::sqrt(std::max(0.0, 1.0 - u1)) * n;
}

// Offset past a surface at p, in Embree's float arithmetic.
double surfaceEpsilon(const Vec3& p) { return 1e-6 * std::max(1.0, p.cwiseAbs().maxCoeff()); }

class PathTracer {
 public:
  PathTracer(const PreparedScene& ps, RenderResult& acc, core::FastRng& rng, bool uniform_shifts)
      : ps_(ps), s_(*ps.spec), acc_(acc), rng_(rng), uniform_shifts_(uniform_shifts) {}

  void emit(const Light& l, double energy) {
    Photon ph;
    ph.energy = energy;
    // Wavelength: the laser line, or λ ∝ x̄ + ȳ + z̄ for an equal-energy spectrum S(λ) = 1/400 per nm.
    if (l.spectrum.kind == Spectrum::Kind::Laser) {
      ph.lambda_nm = l.spectrum.wavelength_nm;
    } else {
      const color::WavelengthSample w = color::sampleWavelength(rng_.uniform(), kVisibleLoNm, kVisibleHiNm);
      ph.lambda_nm = w.wavelength_nm;
      ph.energy *= 1.0 / ((kVisibleHiNm - kVisibleLoNm) * w.pdf_per_nm);
    }
    if (l.kind == Light::Kind::Collimated) {
      ph.o = uniformPoint(l.position_m, l.frame, l.half_x_m, l.half_y_m);
      ph.d = l.frame.n;
    } else if (l.kind == Light::Kind::Area) {
      if (!startArea(l, ph)) return;
    } else if (l.aim >= 0) {
      // Toward a point y drawn uniformly on the target rectangle: the solid-angle pdf is r²/(A cosθ_y), so
      // the isotropic light's share P/(4π)·dω becomes the weight A·cosθ_y/(4π r²).
      ph.o = l.position_m;
      ph.energy *= aimAt(l.aim, ph) / (4.0 * core::kPi);
    } else {
      const double z = 2.0 * rng_.uniform() - 1.0, phi = core::kTwoPi * rng_.uniform();
      const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
      ph.o = l.position_m;
      ph.d = Vec3(r * std::cos(phi), r * std::sin(phi), z);
    }
    trace(ph);
  }

 private:
  // A point drawn uniformly on the rectangle centred on c with the axes of frame f, half-extents hx × hy.
  Vec3 uniformPoint(const Vec3& c, const geometry::Frame& f, double hx, double hy) {
    const double sx = (2.0 * rng_.uniform() - 1.0) * hx, sy = (2.0 * rng_.uniform() - 1.0) * hy;
    return c + sx * f.ex + sy * f.ey;
  }

  // Points ph.d from ph.o to a point y drawn uniformly on target rectangle `target` and returns the
  // geometric factor A·|cosθ_y|/r² (the solid angle per unit pdf: dω = A|cosθ_y|/r² × the area pdf 1/A).
  double aimAt(int target, Photon& ph) {
    const LightScene::Target t = s_.target(target);
    const Vec3 to = uniformPoint(t.frame->origin, *t.frame, t.half_x_m, t.half_y_m) - ph.o;
    const double r2 = to.squaredNorm();
    if (!(r2 > 0)) return 0.0;
    ph.d = to / std::sqrt(r2);
    return 4.0 * t.half_x_m * t.half_y_m * std::abs(ph.d.dot(t.frame->n)) / r2;
  }

  // An area light's start (light_tracer.h): a uniform point x, then a cosine-distributed direction about
  // the emitting face, or toward `aim` with the weight P·cosθ_x·A_t|cosθ_y|/(π r²) (ph.energy carries P).
  // Returns false when the photon carries nothing (aimed behind a one-sided light).
  bool startArea(const Light& l, Photon& ph) {
    ph.o = uniformPoint(l.position_m, l.frame, l.half_x_m, l.half_y_m);
    if (l.aim >= 0) {
      const double g = aimAt(l.aim, ph), cos_x = ph.d.dot(l.frame.n);
      const double emit = l.two_sided ? 0.5 * std::abs(cos_x) : std::max(cos_x, 0.0);
      ph.energy *= emit * g / core::kPi;
      return ph.energy != 0.0;
    }
    // Two-sided: each face emits P/2, so a face drawn with probability 1/2 keeps the photon's energy.
    const bool back = l.two_sided && rng_.uniform() < 0.5;
    const double u1 = rng_.uniform(), u2 = rng_.uniform();
    ph.d = cosineDirection(back ? Vec3(-l.frame.n) : l.frame.n, u1, u2);
    return true;
  }

  void trace(Photon& ph) {
    const geometry::Intersector& isect = ps_.scene.intersector();
    for (int bounce = 0;; ++bounce) {
      if (bounce == s_.settings.max_bounces) {
        acc_.bounce_limit += ph.energy;
        return;
      }
      const geometry::Hit hit = isect.intersect({ph.o, ph.d, ph.tnear, 1e300});
      if (!hit.valid()) {
        acc_.escaped += ph.energy;
        return;
      }
      const transport::Scene::ObjectRef& obj = ps_.scene.object(hit.object);
      // The hit point in double from the object's plane (microns matter on an occluder: Embree's float is not enough).
      const double dn = ph.d.dot(obj.frame.n);
      double t = (obj.origin_n - ph.o.dot(obj.frame.n)) / dn;
      if (!(std::isfinite(t) && t > 0)) t = hit.t;
      const Vec3 p = ph.o + t * ph.d;
      if (obj.kind == ObjectKind::Occluder) {
        if (!scatter(ps_.scene.occluders()[obj.index], obj, p, ph)) return;
      } else if (obj.kind == ObjectKind::Screen) {
        if (!diffuse(s_.rects[obj.index], obj.frame, p, dn, ph)) return;
      } else {
        acc_.absorbed_occluders += ph.energy;  // no other kind is built (render/light_setup.h)
        return;
      }
      ph.o = p;
      ph.tnear = surfaceEpsilon(p);
    }
  }

  bool scatter(const transport::Occluder& occ, const transport::Scene::ObjectRef& obj, const Vec3& p, Photon& ph) {
    const double x = p.dot(obj.frame.ex) - obj.origin_x, y = p.dot(obj.frame.ey) - obj.origin_y;
    const double xi_x = rng_.uniform(), xi_y = rng_.uniform();
    double weight = 0.0;
    const transport::ScatterFate fate =
        transport::scatterAtOccluder(occ, obj.frame, x, y, ph.lambda_nm * 1e-9, xi_x, xi_y, ph.d.data(), weight,
                                    uniform_shifts_);
    if (fate == transport::ScatterFate::Absorbed) {
      acc_.absorbed_occluders += ph.energy;
      return false;
    }
    ph.energy *= weight;
    if (occ.reflect && fate != transport::ScatterFate::Evanescent) {
      // The metal layer keeps `reflectance` of the power; the rest counts as absorbed by the occluder.
      const double kept = ph.energy * s_.occluders[obj.index].reflectance;
      acc_.absorbed_occluders += ph.energy - kept;
      ph.energy = kept;
    }
    if (fate == transport::ScatterFate::Evanescent) {
      acc_.evanescent += ph.energy;
      return false;
    }
    return true;
  }

  // Scores the photon at diffuse point p (the measurement of light_tracer.h), then continues it or not.
  bool diffuse(const DiffuseRect& rect, const geometry::Frame& f, const Vec3& p, double dn, Photon& ph) {
    acc_.on_diffuse += ph.energy;
    const Vec3 lit = dn < 0 ? f.n : Vec3(-f.n);  // the face the photon arrived on
    const double albedo = rect.albedo.at(ph.lambda_nm);
    const Camera::Projection pr = ps_.camera.project(p);
    if (pr.inside()) {
      const double cos_s = lit.dot(pr.to_camera);
      if (cos_s > 0 && visible(p, pr)) {
        const std::size_t pix = static_cast<std::size_t>(pr.iy) * ps_.camera.width() + pr.ix;
        const double dP = ph.energy * albedo / core::kPi * cos_s / (pr.distance_m * pr.distance_m) /
                          ps_.pixel_solid_angle_sr[pix];
        const color::Xyz c = color::cie1931(ph.lambda_nm);
        acc_.xyz[3 * pix] += dP * c.x;
        acc_.xyz[3 * pix + 1] += dP * c.y;
        acc_.xyz[3 * pix + 2] += dP * c.z;
        acc_.radiance.add(static_cast<int>(pix), dP);
        (dP >= 0 ? acc_.scored_positive : acc_.scored_negative) += std::abs(dP);
        ++acc_.camera_scores;
      }
    }
    // Russian roulette on the albedo: the survivor keeps its energy (ρ/ρ), leaving in a cosine lobe.
    if (ph.diffuse_bounces >= s_.settings.diffuse_bounces || !(rng_.uniform() < albedo)) {
      acc_.absorbed_diffuse += ph.energy;
      return false;
    }
    ++ph.diffuse_bounces;
    const double u1 = rng_.uniform(), u2 = rng_.uniform();
    ph.d = cosineDirection(lit, u1, u2);
    return true;
  }

  // Whether nothing lies between p and the pinhole.
  bool visible(const Vec3& p, const Camera::Projection& pr) const {
    const double eps = surfaceEpsilon(p);
    const geometry::Hit h = ps_.scene.intersector().intersect({p, pr.to_camera, eps, pr.distance_m});
    return !h.valid() || h.t >= pr.distance_m * (1.0 - 1e-6);
  }

  const PreparedScene& ps_;
  const LightScene& s_;
  RenderResult& acc_;
  core::FastRng& rng_;
  bool uniform_shifts_;
};

}  // namespace

std::uint64_t sppPhotons(std::uint64_t spp, int width, int height) {
  const double photons = static_cast<double>(spp) * width * height;  // in double: no uint64 wrap-around
  if (!(photons <= 1e13))
    throw core::InputError("--spp", std::to_string(spp) + " per pixel × " + std::to_string(width) + "×" +
                                        std::to_string(height) + " pixels is over the limit of 1e13 photons");
  return spp * static_cast<std::uint64_t>(width) * static_cast<std::uint64_t>(height);
}

double renderPeakBytes(int width, int height, int threads) {
  // Alive at once (core::orderedReduce): the total plus one accumulator per thread, each holding xyz (3
  // doubles) and the radiance tally's sum and sum_sq per pixel; a chunk being traced adds its scratch
  // (1 double per pixel); then linearSrgb's image (3 floats) and PNG bytes (3) are small beside that.
  const double pixels = static_cast<double>(width) * height;
  const double accumulators = 1.0 + std::max(1, threads);
  return pixels * (kAccumulatorBytesPerPixel * accumulators + 8.0 * std::max(1, threads));
}

void checkRenderMemory(int width, int height, int threads, double physical_bytes) {
  const double need = renderPeakBytes(width, height, threads);
  if (physical_bytes > 0 && need > 0.5 * physical_bytes) {
    char what[256];
    std::snprintf(what, sizeof what,
                  "a %d×%d image with %d threads needs about %.1f GB, over half of this machine's %.1f GB; use "
                  "fewer pixels or fewer --threads",
                  width, height, threads, need / 1e9, physical_bytes / 1e9);
    throw core::InputError("camera.pixels", what);
  }
}

RenderResult renderLight(const PreparedScene& ps, const RenderOptions& options) {
  DIFFRAY_CHECK(ps.spec != nullptr);
  const LightScene& s = *ps.spec;
  if (options.photons == 0) throw core::InputError("--photons", "must be > 0");
  if (s.lights.empty()) throw core::InputError(s.file, "the scene has no light");
  std::vector<double> cdf;  // lights picked ∝ power
  double total = 0.0;
  for (const Light& l : s.lights) cdf.push_back(total += l.power_w);
  const double photon_energy = total / static_cast<double>(options.photons);
  const int npix = ps.camera.width() * ps.camera.height();
  checkRenderMemory(ps.camera.width(), ps.camera.height(), core::ThreadLimit::current(), core::physicalMemoryBytes());

  auto make = [&] {
    RenderResult r;
    r.width = ps.camera.width();
    r.height = ps.camera.height();
    r.xyz.assign(3 * static_cast<std::size_t>(npix), 0.0);
    r.radiance = receiver::ScreenTally(npix);
    r.radiance.chunk = {};  // the open chunk's scratch lives only while a chunk is traced (body below)
    return r;
  };
  auto body = [&](RenderResult& acc, core::Rng& chunk_rng, std::uint64_t begin, std::uint64_t end) {
    core::FastRng rng(chunk_rng);
    acc.radiance.chunk.assign(static_cast<std::size_t>(npix), 0.0);
    PathTracer tracer(ps, acc, rng, options.uniform_shifts);
    for (std::uint64_t i = begin; i < end; ++i) {
      const double pick = rng.uniform() * total;
      const std::size_t l = std::min<std::size_t>(
          static_cast<std::size_t>(std::upper_bound(cdf.begin(), cdf.end(), pick) - cdf.begin()), cdf.size() - 1);
      acc.emitted += photon_energy;
      ++acc.photons;
      tracer.emit(s.lights[l], photon_energy);
    }
    acc.radiance.closeChunk();
    acc.radiance.chunk = {};
  };
  return core::orderedReduce<RenderResult>(options.photons, options.chunk_photons, options.seed, make, body,
                                                 core::reportProgressTo(options.on_progress));
}

}  // namespace diffray::render
