#include "diffray/transport/scene.h"

#include <cmath>

#include "diffray/core/error.h"

namespace diffray::transport {

double CollimatedSource::power() const {
  return intensity * 4.0 * half_x_m * half_y_m * std::abs(dir.normalized().dot(frame.n));
}

int Scene::addObject(ObjectKind kind, int index, const geometry::Frame& f, double hx, double hy) {
  core::requirePositive("object half-width", hx);
  core::requirePositive("object half-height", hy);
  const int id = static_cast<int>(objects_.size());
  objects_.push_back({kind, index, f, f.origin.dot(f.n), f.origin.dot(f.ex), f.origin.dot(f.ey)});
  mesh_.addRect(f.origin, f.ex * hx, f.ey * hy, id);
  return id;
}

int Scene::addOccluder(Occluder o) {
  if (!o.table_x) throw core::InputError("occluder", "needs a WBSDF table along x");
  occluders_.push_back(std::move(o));
  const auto& b = occluders_.back();
  return addObject(ObjectKind::Occluder, static_cast<int>(occluders_.size()) - 1, b.frame, b.half_x_m, b.half_y_m);
}

int Scene::addScreen(receiver::Screen s) {
  if (s.nx < 1 || s.ny < 1) throw core::InputError("screen", "needs at least one bin along x and y");
  screens_.push_back(s);
  return addObject(ObjectKind::Screen, static_cast<int>(screens_.size()) - 1, s.frame, s.half_x_m, s.half_y_m);
}

int Scene::addSphere(receiver::Sphere s) {
  core::requirePositive("sphere radius", s.radius_m);
  for (int c = 0; c < 3; ++c) core::requireFinite("sphere centre", s.centre[c]);
  spheres_.push_back(s);
  return static_cast<int>(spheres_.size()) - 1;
}

void Scene::setFarField(FarField f) {
  if (f.bins < 1 || !(f.alpha_hi > f.alpha_lo)) throw core::InputError("far field", "needs bins >= 1 and a range");
  f.ex = f.ex.normalized();
  far_field_ = f;
}

int Scene::addAbsorber(Absorber a) {
  absorbers_.push_back(a);
  return addObject(ObjectKind::Absorber, static_cast<int>(absorbers_.size()) - 1, a.frame, a.half_x_m, a.half_y_m);
}

void Scene::build(bool brute_force) {
  if (brute_force)
    intersector_ = std::make_unique<geometry::BruteForceScene>(mesh_);
  else
    intersector_ = std::make_unique<geometry::EmbreeScene>(mesh_);
}

}  // namespace diffray::transport
