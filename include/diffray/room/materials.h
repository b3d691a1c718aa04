#pragma once
// Materials in scene files and in the material library (rooms/materials.json). Coefficients are
// given per octave band, 63 Hz to 8 kHz (8 values), as a single number (the same in every band), an
// array of 8, or an object keyed by the nominal centres {"63": …, "125": …, …, "8000": …} (all 8).
// They are resampled to the room's bands: octave bands take them as they are; third-octave bands
// interpolate linearly in log-frequency between the octave centres and hold the end values beyond
// 63 Hz and 8 kHz. Checks: every value in [0, 1], transmission ≤ absorption band by band.
// Free functions on plain data; thread-safe.
#include <array>
#include <map>
#include <string>

#include "diffray/core/bands.h"
#include "diffray/room/json_fields.h"
#include "diffray/room/room.h"

namespace diffray::room {

inline constexpr int kOctaveCount = 8;  ///< octave bands 63 Hz … 8 kHz
using OctaveValues = std::array<double, kOctaveCount>;

/// Nominal octave centres, 63 … 8000 Hz.
const std::array<double, kOctaveCount>& octaveNominalHz();

/// Octave values resampled to `bands` (see the file comment).
core::BandArray resampleOctaves(const OctaveValues& octave, const core::Bands& bands);

/// A per-band coefficient in [0, 1] in one of the three forms above.
OctaveValues parseOctaveValues(const JsonField& field);

/// A material object {"absorption", "scattering", "transmission" (default 0), "description",
/// "source"}; absorption and scattering are required. `require_source` is set for the library, whose
/// every entry must say where its figures come from.
Material parseMaterial(const JsonField& field, const std::string& name, const core::Bands& bands,
                       bool require_source = false);

/// The library file {"description": …, "materials": {name: material, …}}, resampled to `bands`.
std::map<std::string, Material> loadMaterialLibrary(const std::string& path, const core::Bands& bands);

}  // namespace diffray::room
