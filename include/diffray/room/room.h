#pragma once
// A room as diffray simulates it: triangle geometry whose triangles each carry a material, the
// materials' per-band coefficients, sound sources, listeners, the air, and what to output. Units: metres,
// watts, seconds, Hz, °C, %, kPa; positions in the scene file's (world) frame. Everything per band is
// already resampled to `bands`. Built by loadRoom() (room/scene_file.h) or in code (tests, validation
// cases); plain data, immutable once built, safe to share between threads.
#include <cstdint>
#include <string>
#include <vector>

#include "diffray/core/bands.h"
#include "diffray/core/math.h"
#include "diffray/geometry/mesh.h"
#include "diffray/room/occluder.h"

namespace diffray::room {

using core::Vec3;

/// A surface's acoustic properties, one value per band. absorption α is the fraction of
/// incident energy not reflected; transmission τ ≤ α is the part of it that passes through the surface
/// (the rest, α − τ, is lost); scattering s is the fraction of the reflected energy that leaves as a
/// Lambert (cosine) lobe instead of specularly (ISO 17497-1).
struct Material {
  std::string name;
  core::BandArray absorption = core::bandFill(0.0);
  core::BandArray scattering = core::bandFill(0.0);
  core::BandArray transmission = core::bandFill(0.0);
  std::string reference;  ///< where the figures come from (for the library; may be empty)
};

/// A first-order source pattern: pressure amplitude a + (1 − a)·cos θ about `axis` (a = 1 omni,
/// 0.5 cardioid, 0 dipole); radiated power is normalised so that `power_w` is the total in every band.
struct Directivity {
  double a = 1.0;
  Vec3 axis{1, 0, 0};
  std::string pattern = "omni";  ///< the name given in the file
};

struct Source {
  std::string name;
  Vec3 position_m{0, 0, 0};
  double power_w = 1.0;
  Directivity directivity;
};

struct Listener {
  std::string name;
  Vec3 position_m{0, 0, 0};
  double radius_m = 0.1;
  /// The listener's head frame, world coordinates, orthonormal and right-handed: forward, left, up (the
  /// scene's "orientation" or "look_at", rooms/README.md). Default: facing +x, +z up.
  Vec3 forward{1, 0, 0}, left{0, 1, 0}, up{0, 0, 1};
  /// A world vector in the listener's frame: x forward, y left, z up (the frame of AmbiX and of ISO 2631's
  /// head coordinates), so azimuth atan2(y, x) grows to the left and elevation upwards.
  Vec3 toLocal(const Vec3& w) const { return {w.dot(forward), w.dot(left), w.dot(up)}; }
};

struct Air {
  double temperature_c = 20.0;
  double humidity_percent = 50.0;
  double pressure_kpa = 101.325;
  /// 0: the speed of sound follows the temperature (core::speedOfSound); otherwise this value (m/s), e.g. to
  /// match a reference computed with c = 340 or 343 m/s. Air absorption always follows the temperature.
  double speed_of_sound_m_s = 0.0;
};

struct Output {
  double sample_rate_hz = 48000.0;
  /// IR length; 0 = until the decay has fallen by 60 dB (estimated from the room, capped at max_length_s).
  double ir_length_s = 0.0;
  double max_length_s = 10.0;
  double histogram_bin_s = 0.001;  ///< band × time histogram resolution (≤ 1 ms)
  int ism_order = 3;               ///< image sources up to this reflection order (0 = direct sound only)
  std::uint64_t rays = 1000000;    ///< default ray count (the CLI's --rays overrides it)
  std::uint64_t seed = 1;
};

struct Room {
  std::string name;
  std::string file;  ///< where it was loaded from (empty when built in code)
  /// Every file read to build it: the scene file, its material library, its OBJ meshes (outputs must not
  /// replace any of them).
  std::vector<std::string> input_files;
  core::Bands bands = core::Bands::octave();
  std::vector<Material> materials;
  /// Triangles; mesh.object_of_triangle[i] is the index of triangle i's material in `materials`.
  geometry::Mesh mesh;
  /// Name of each triangle's group (OBJ group / primitive name), for messages; parallel to triangles.
  std::vector<std::string> group_of_triangle;
  std::vector<Source> sources;
  std::vector<Listener> listeners;
  /// WBSDF occluders (doors, slits, edges, gratings): used when diffraction is "wbsdf"; otherwise their
  /// triangles are plain surfaces (an opening passes rays straight, a grating reflects like its material).
  std::vector<Occluder> occluders;
  Air air;
  Output output;

  /// Adds a material and returns its index.
  int addMaterial(Material m) {
    materials.push_back(std::move(m));
    return static_cast<int>(materials.size()) - 1;
  }
  /// Adds an axis-aligned box room [lo, hi] with inward-facing walls, each wall one material index:
  /// order x−, x+, y−, y+, z− (floor), z+ (ceiling).
  void addBox(const Vec3& lo, const Vec3& hi, const int material_of_wall[6], const std::string& group = "box");
  /// Adds a planar convex or concave simple polygon (vertices in order), fan-free ear-clipping triangulation.
  void addPolygon(const std::vector<Vec3>& vertices, int material, const std::string& group);
  /// Whether material `m` transmits everything in every band (an opening such as an open doorway):
  /// such surfaces are not part of the enclosure.
  bool isOpening(int m) const;
  /// Which triangles bound the enclosed air (1) or not (0): every triangle but the openings, unless
  /// the openings are needed to close it (an open window to the outside): of the two sets, the one
  /// whose vector area Σ n·dA is nearer zero, as it is for a closed surface (the condition for the
  /// volume's divergence sum not to depend on the origin). A doorway between two rooms is left out.
  std::vector<char> enclosure() const;
  /// Volume (m³, by the divergence theorem over enclosure(); meaningful for a closed mesh) and total
  /// surface area (m², openings included).
  double volume() const;
  double surfaceArea() const;
};

}  // namespace diffray::room
