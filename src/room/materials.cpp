#include "diffray/room/materials.h"

#include <cmath>

#include "diffray/core/error.h"

namespace diffray::room {

namespace {

std::string octaveKey(int i) { return formatNumber(octaveNominalHz()[i]); }

// The part of a coefficient field that holds band i (the field itself for a single number).
JsonField bandField(const JsonField& f, int i) {
  if (f.json().is_array()) return f.at(static_cast<std::size_t>(i));
  if (f.json().is_object()) return f[octaveKey(i)];
  return f;
}

}  // namespace

const std::array<double, kOctaveCount>& octaveNominalHz() {
  static const std::array<double, kOctaveCount> nominal = {63, 125, 250, 500, 1000, 2000, 4000, 8000};
  return nominal;
}

core::BandArray resampleOctaves(const OctaveValues& octave, const core::Bands& bands) {
  core::BandArray out = core::bandFill(0.0);
  for (int b = 0; b < bands.size(); ++b) {
    // Position on the octave axis: exact IEC centres are 1000·10^(0.3 k), so 63 Hz is x = 0 and
    // 8 kHz is x = 7; third-octave centres fall on thirds exactly.
    double x = std::log10(bands.centreHz(b) / 1000.0) / 0.3 + 4.0;
    if (std::abs(x - std::round(x)) < 1e-9) x = std::round(x);
    if (x <= 0.0) {
      out[b] = octave[0];
    } else if (x >= kOctaveCount - 1) {
      out[b] = octave[kOctaveCount - 1];
    } else {
      const int i = static_cast<int>(std::floor(x));
      const double t = x - i;
      out[b] = t == 0.0 ? octave[i] : (1.0 - t) * octave[i] + t * octave[i + 1];
    }
  }
  return out;
}

OctaveValues parseOctaveValues(const JsonField& field) {
  OctaveValues v{};
  const auto& j = field.json();
  if (j.is_array()) {
    field.arraySize(kOctaveCount);
    for (int i = 0; i < kOctaveCount; ++i) v[i] = field.at(i).numberIn(0.0, 1.0);
  } else if (j.is_object()) {
    field.allowKeys({"63", "125", "250", "500", "1000", "2000", "4000", "8000"});
    for (int i = 0; i < kOctaveCount; ++i) v[i] = field[octaveKey(i)].numberIn(0.0, 1.0);
  } else if (j.is_number()) {
    v.fill(field.numberIn(0.0, 1.0));
  } else {
    field.fail("must be a number, an array of 8 octave values (63 Hz … 8 kHz) or an object {\"63\": …, "
               "\"8000\": …}, got " + describeJson(j));
  }
  return v;
}

Material parseMaterial(const JsonField& field, const std::string& name, const core::Bands& bands,
                       bool require_source) {
  field.allowKeys({"absorption", "scattering", "transmission", "description", "source"});
  Material m;
  m.name = name;
  const OctaveValues absorption = parseOctaveValues(field["absorption"]);
  const OctaveValues scattering = parseOctaveValues(field["scattering"]);
  OctaveValues transmission{};
  if (field.has("transmission")) {
    const JsonField t = field["transmission"];
    transmission = parseOctaveValues(t);
    for (int i = 0; i < kOctaveCount; ++i)
      if (transmission[i] > absorption[i])
        bandField(t, i).fail("must not exceed the absorption in the same band (" + formatNumber(octaveNominalHz()[i]) +
               " Hz: transmission " + formatNumber(transmission[i]) + " > absorption " +
               formatNumber(absorption[i]) + "): transmitted energy is part of the absorbed energy");
  }
  if (field.has("description")) field["description"].string();
  if (field.has("source")) m.reference = field["source"].string();
  else if (require_source) field["source"];  // throws "missing (required)"
  m.absorption = resampleOctaves(absorption, bands);
  m.scattering = resampleOctaves(scattering, bands);
  m.transmission = resampleOctaves(transmission, bands);
  return m;
}

std::map<std::string, Material> loadMaterialLibrary(const std::string& path, const core::Bands& bands) {
  const nlohmann::json doc = parseJsonFile(path);
  const JsonField top(doc, path);
  top.allowKeys({"description", "materials"});
  if (top.has("description")) top["description"].string();
  const JsonField list = top["materials"];
  std::map<std::string, Material> out;
  for (const std::string& name : list.keys()) out[name] = parseMaterial(list[name], name, bands, true);
  return out;
}

}  // namespace diffray::room
