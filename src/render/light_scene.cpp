#include "diffray/render/light_scene.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "diffray/core/error.h"
#include "diffray/room/json_fields.h"

namespace diffray::render {

using room::JsonField;

double Albedo::at(double nm) const {
  if (wavelengths_nm.empty()) return values.front();
  if (nm <= wavelengths_nm.front()) return values.front();
  if (nm >= wavelengths_nm.back()) return values.back();
  const auto it = std::upper_bound(wavelengths_nm.begin(), wavelengths_nm.end(), nm);
  const std::size_t i = static_cast<std::size_t>(it - wavelengths_nm.begin());
  const double f = (nm - wavelengths_nm[i - 1]) / (wavelengths_nm[i] - wavelengths_nm[i - 1]);
  return values[i - 1] + f * (values[i] - values[i - 1]);
}

double Albedo::max() const { return *std::max_element(values.begin(), values.end()); }

LightScene::Target LightScene::target(int i) const {
  DIFFRAY_CHECK(i >= 0 && i < targetCount());
  const std::size_t n = rects.size();
  if (static_cast<std::size_t>(i) < n) return {&rects[i].frame, rects[i].half_x_m, rects[i].half_y_m};
  const OccluderSpec& o = occluders[i - n];
  return {&o.frame, o.half_x_m, o.half_y_m};
}

double LightScene::shortestWavelengthNm() const {
  double lo = kVisibleHiNm;
  for (const Light& l : lights) lo = std::min(lo, l.spectrum.loNm());
  return lo;
}

double LightScene::longestWavelengthNm() const {
  double hi = kVisibleLoNm;
  for (const Light& l : lights) hi = std::max(hi, l.spectrum.hiNm());
  return hi;
}

geometry::Frame rectFrame(const Vec3& centre, const Vec3& normal, const Vec3& up, const std::string& field) {
  if (!(normal.norm() > 0)) throw core::InputError(field + ".normal", "must be a non-zero vector");
  geometry::Frame f;
  f.origin = centre;
  f.n = normal.normalized();
  const Vec3 ey = up - up.dot(f.n) * f.n;
  if (!(ey.norm() > 1e-9 * std::max(1.0, up.norm())))
    throw core::InputError(field + ".up", "must be non-zero and not parallel to the normal");
  f.ey = ey.normalized();
  f.ex = f.ey.cross(f.n);
  return f;
}

namespace {

Vec3 optionalVec(const JsonField& f, const char* key, const Vec3& fallback) {
  return f.has(key) ? f[key].vec3() : fallback;
}

// The rectangle keys shared by rectangles and occluders: centre, normal, up, width_m, height_m.
void parseRect(const JsonField& f, geometry::Frame& frame, double& half_x, double& half_y) {
  frame = rectFrame(f["centre"].vec3(), f["normal"].vec3(), optionalVec(f, "up", Vec3(0, 1, 0)), f.where());
  half_x = 0.5 * f["width_m"].length();
  half_y = 0.5 * f["height_m"].length();
}

Albedo parseAlbedo(const JsonField& f) {
  Albedo a;
  if (f.json().is_number()) {
    a.values = {f.numberIn(0.0, 1.0)};
    return a;
  }
  f.allowKeys({"wavelengths_nm", "values"});
  const JsonField w = f["wavelengths_nm"], v = f["values"];
  const std::size_t n = w.arraySize();
  if (n < 1) w.fail("needs at least one wavelength");
  v.arraySize(static_cast<int>(n));
  a.values.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const double nm = w.at(i).numberIn(300.0, 900.0);
    if (i > 0 && !(nm > a.wavelengths_nm.back())) w.at(i).fail("wavelengths must increase");
    a.wavelengths_nm.push_back(nm);
    a.values.push_back(v.at(i).numberIn(0.0, 1.0));
  }
  return a;
}

Spectrum parseSpectrum(const JsonField& light, Spectrum::Kind fallback) {
  Spectrum s;
  s.kind = fallback;
  if (light.has("spectrum")) {
    const std::string k = light["spectrum"].string();
    if (k == "white") s.kind = Spectrum::Kind::White;
    else if (k == "laser") s.kind = Spectrum::Kind::Laser;
    else light["spectrum"].fail("must be \"white\" or \"laser\", got \"" + k + "\"");
  }
  if (s.kind == Spectrum::Kind::Laser) {
    if (!light.has("wavelength_nm")) light["wavelength_nm"];  // fails: missing (required)
    s.wavelength_nm = light["wavelength_nm"].numberIn(kVisibleLoNm, kVisibleHiNm);
  } else if (light.has("wavelength_nm")) {
    light["wavelength_nm"].fail("only a \"laser\" spectrum has a wavelength");
  }
  return s;
}

OccluderSpec parseOccluder(const JsonField& f, int index) {
  OccluderSpec o;
  const std::string type = f["type"].string();
  if (type == "slit") {
    f.allowKeys({"type", "name", "centre", "normal", "up", "width_m", "height_m", "slit_width_m", "slit_height_m"});
    o.kind = OccluderSpec::Kind::Slit;
  } else if (type == "double-slit") {
    f.allowKeys({"type", "name", "centre", "normal", "up", "width_m", "height_m", "slit_width_m", "slit_height_m",
                 "spacing_m"});
    o.kind = OccluderSpec::Kind::DoubleSlit;
  } else if (type == "aperture") {
    f.allowKeys({"type", "name", "centre", "normal", "up", "width_m", "height_m", "aperture_width_m",
                 "aperture_height_m"});
    o.kind = OccluderSpec::Kind::Aperture;
  } else if (type == "grating") {
    f.allowKeys({"type", "name", "centre", "normal", "up", "width_m", "height_m", "period_m", "modulation",
                 "reflectance"});
    o.kind = OccluderSpec::Kind::Grating;
  } else if (type == "lens") {
    f.allowKeys({"type", "name", "centre", "normal", "up", "width_m", "height_m", "aperture_width_m",
                 "aperture_height_m", "focal_length_m"});
    o.kind = OccluderSpec::Kind::Lens;
  } else {
    f["type"].fail("unknown occluder type \"" + type + "\" (types: slit, double-slit, aperture, grating, lens)");
  }
  o.name = f.has("name") ? f["name"].string() : type + std::to_string(index + 1);
  parseRect(f, o.frame, o.half_x_m, o.half_y_m);
  switch (o.kind) {
    case OccluderSpec::Kind::DoubleSlit:
      o.spacing_m = f["spacing_m"].length();
      [[fallthrough]];
    case OccluderSpec::Kind::Slit: {
      o.slit_width_m = f["slit_width_m"].length();
      if (f.has("slit_height_m")) o.slit_height_m = f["slit_height_m"].length();
      if (o.kind == OccluderSpec::Kind::DoubleSlit && !(o.spacing_m > o.slit_width_m))
        f["spacing_m"].fail("must exceed slit_width_m (the slits would overlap)");
      const double span = o.slit_width_m + o.spacing_m;
      if (span > 2.0 * o.half_x_m) f["width_m"].fail("the slits do not fit in the occluder's width");
      if (o.slit_height_m > 2.0 * o.half_y_m) f["slit_height_m"].fail("exceeds the occluder's height_m");
      break;
    }
    case OccluderSpec::Kind::Lens:
      o.focal_length_m = f["focal_length_m"].length();
      [[fallthrough]];
    case OccluderSpec::Kind::Aperture:
      o.aperture_width_m = f["aperture_width_m"].length();
      o.aperture_height_m = f["aperture_height_m"].length();
      if (o.aperture_width_m > 2.0 * o.half_x_m) f["aperture_width_m"].fail("exceeds the occluder's width_m");
      if (o.aperture_height_m > 2.0 * o.half_y_m) f["aperture_height_m"].fail("exceeds the occluder's height_m");
      break;
    case OccluderSpec::Kind::Grating:
      o.period_m = f["period_m"].length();
      o.modulation = f["modulation"].numberIn(0.0, 1000.0);
      if (f.has("reflectance")) o.reflectance = f["reflectance"].numberIn(0.0, 1.0);
      break;
  }
  return o;
}

// The index of the rectangle or occluder named by `aim` (point and area lights).
int parseAim(const JsonField& f, const std::vector<std::string>& target_names) {
  const std::string t = f["aim"].string();
  const auto it = std::find(target_names.begin(), target_names.end(), t);
  if (it == target_names.end()) f["aim"].fail("no rectangle or occluder is named \"" + t + "\"");
  return static_cast<int>(it - target_names.begin());
}

Light parseLight(const JsonField& f, int index, const std::vector<std::string>& target_names) {
  Light l;
  const std::string type = f["type"].string();
  if (type == "point") {
    f.allowKeys({"type", "name", "position", "power_w", "spectrum", "wavelength_nm", "aim"});
    l.kind = Light::Kind::Point;
    l.spectrum = parseSpectrum(f, Spectrum::Kind::White);
    l.position_m = f["position"].vec3();
  } else if (type == "laser") {
    f.allowKeys({"type", "name", "position", "direction", "up", "width_m", "height_m", "power_w", "spectrum",
                 "wavelength_nm"});
    l.kind = Light::Kind::Collimated;
    l.spectrum = parseSpectrum(f, Spectrum::Kind::Laser);
    l.position_m = f["position"].vec3();
    l.frame = rectFrame(l.position_m, f["direction"].vec3(), optionalVec(f, "up", Vec3(0, 1, 0)), f.where());
    l.half_x_m = 0.5 * f["width_m"].length();
    l.half_y_m = f.has("height_m") ? 0.5 * f["height_m"].length() : l.half_x_m;
  } else if (type == "area") {
    f.allowKeys({"type", "name", "centre", "normal", "up", "width_m", "height_m", "power_w", "spectrum",
                 "wavelength_nm", "two_sided", "aim"});
    l.kind = Light::Kind::Area;
    l.spectrum = parseSpectrum(f, Spectrum::Kind::White);
    parseRect(f, l.frame, l.half_x_m, l.half_y_m);
    l.position_m = l.frame.origin;
    if (f.has("two_sided")) l.two_sided = f["two_sided"].boolean();
  } else {
    f["type"].fail("unknown light type \"" + type + "\" (types: point, laser, area)");
  }
  if (f.has("aim")) l.aim = parseAim(f, target_names);  // point and area lights (allowKeys above)
  l.name = f.has("name") ? f["name"].string() : type + std::to_string(index + 1);
  l.power_w = f.has("power_w") ? f["power_w"].positive() : 1.0;
  return l;
}

CameraSpec parseCamera(const JsonField& f) {
  f.allowKeys({"position", "look_at", "up", "fov_deg", "pixels"});
  CameraSpec c;
  c.position_m = f["position"].vec3();
  c.look_at_m = f["look_at"].vec3();
  c.up = optionalVec(f, "up", Vec3(0, 1, 0));
  c.fov_x_deg = f["fov_deg"].numberIn(1e-6, 170.0);
  const JsonField px = f["pixels"];
  px.arraySize(2);
  c.width = static_cast<int>(px.at(0).integerIn(1, 16384));
  c.height = static_cast<int>(px.at(1).integerIn(1, 16384));
  try {
    Camera check(c);
  } catch (const core::InputError& e) {
    throw core::InputError(f.file(), e.what());  // Camera names the field (camera.up): not "camera: camera.up"
  }
  return c;
}

RenderSettings parseSettings(const JsonField& f) {
  f.allowKeys({"photons", "seed", "max_bounces", "diffuse_bounces", "exposure"});
  RenderSettings s;
  if (f.has("photons")) s.photons = static_cast<std::uint64_t>(f["photons"].integerIn(1, 10'000'000'000'000));
  if (f.has("seed")) s.seed = static_cast<std::uint64_t>(f["seed"].integerIn(0, 1'000'000'000'000'000));
  if (f.has("max_bounces")) s.max_bounces = static_cast<int>(f["max_bounces"].integerIn(1, 256));
  if (f.has("diffuse_bounces")) s.diffuse_bounces = static_cast<int>(f["diffuse_bounces"].integerIn(0, 64));
  if (f.has("exposure")) {
    const JsonField e = f["exposure"];
    if (e.json().is_string()) {
      if (e.string() != "auto") e.fail("must be a number > 0 or \"auto\"");
    } else {
      s.exposure = e.positive();
    }
  }
  return s;
}

}  // namespace

namespace {

LightScene fromJson(const nlohmann::json& doc, const std::string& file) {
  const JsonField top(doc, file);
  top.allowKeys({"name", "description", "rectangles", "occluders", "lights", "camera", "render"});
  LightScene scene;
  scene.file = file;
  scene.name = top.has("name") ? top["name"].string() : file;
  std::vector<std::string> names;
  std::set<std::string> unique;
  auto addName = [&](const JsonField& f, const std::string& name) {
    if (!unique.insert(name).second) f.fail("the name \"" + name + "\" is used twice");
    names.push_back(name);
  };
  if (top.has("rectangles")) {
    const JsonField list = top["rectangles"];
    for (std::size_t i = 0; i < list.arraySize(); ++i) {
      const JsonField f = list.at(i);
      f.allowKeys({"name", "centre", "normal", "up", "width_m", "height_m", "albedo"});
      DiffuseRect r;
      r.name = f.has("name") ? f["name"].string() : "rect" + std::to_string(i + 1);
      parseRect(f, r.frame, r.half_x_m, r.half_y_m);
      if (f.has("albedo")) r.albedo = parseAlbedo(f["albedo"]);
      addName(f, r.name);
      scene.rects.push_back(std::move(r));
    }
  }
  if (top.has("occluders")) {
    const JsonField list = top["occluders"];
    for (std::size_t i = 0; i < list.arraySize(); ++i) {
      scene.occluders.push_back(parseOccluder(list.at(i), static_cast<int>(i)));
      addName(list.at(i), scene.occluders.back().name);
    }
  }
  if (scene.rects.empty()) top["rectangles"].fail("needs at least one diffuse rectangle (nothing would be seen)");
  const JsonField lights = top["lights"];
  for (std::size_t i = 0; i < lights.arraySize(); ++i)
    scene.lights.push_back(parseLight(lights.at(i), static_cast<int>(i), names));
  if (scene.lights.empty()) lights.fail("needs at least one light");
  scene.camera = parseCamera(top["camera"]);
  if (top.has("render")) scene.settings = parseSettings(top["render"]);
  return scene;
}

}  // namespace

LightScene parseLightScene(const std::string& text, const std::string& file) {
  return fromJson(room::parseJsonText(text, file), file);
}

LightScene loadLightScene(const std::string& path) { return fromJson(room::parseJsonFile(path), path); }

}  // namespace diffray::render
