#include "diffray/room/scene_file.h"

#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "diffray/core/error.h"
#include "diffray/room/checks.h"
#include "diffray/room/json_fields.h"
#include "diffray/room/materials.h"
#include "diffray/room/obj.h"
#include "diffray/room/occluder_file.h"

namespace diffray::room {
namespace {

std::string joinPath(const std::string& dir, const std::string& rel) {
  if (rel.empty() || rel[0] == '/' || dir.empty() || dir == ".") return rel;
  return dir.back() == '/' ? dir + rel : dir + "/" + rel;
}

std::string inQuotes(const std::string& s) { return "\"" + s + "\""; }

// A file a scene field names (an OBJ, the material library): it must exist and be a regular file.
void requireInputFile(const JsonField& field, const std::string& path, const std::string& what) {
  if (const std::string why = notRegularFile(path); !why.empty()) field.fail(path + " " + why + ", not " + what);
  if (!std::ifstream(path)) field.fail("cannot open " + what + " " + path);
}

// A source's or listener's name: unique among its kind (a default name "S2" may clash with a given one, so
// the entry is blamed when it has no "name") and free of what would break the histogram CSV's header.
void claimName(std::set<std::string>& names, const std::string& name, const JsonField& entry, const char* kind) {
  const JsonField at = entry.has("name") ? entry["name"] : entry;
  if (name.find_first_of(",\"\n\r") != std::string::npos)
    at.fail(std::string(kind) + " name " + nlohmann::json(name).dump() + " must not contain a comma, a quote or a line break "
            "(it heads a column of the histogram CSV)");
  if (!names.insert(name).second) at.fail(std::string("duplicate ") + kind + " name " + inQuotes(name));
}

// Half the width of ir::BandFilter's crossover above the top band (its default 40 Hz transition).
constexpr double kTopCrossoverHalfWidthHz = 20.0;  // tied by IrBandFilter.TopBandNeedsTheRateTheSceneLoaderAsksFor

// Everything the parts of the scene need: the room being built and how material names resolve.
struct SceneParser {
  std::string file, base_dir;
  Room& room;
  std::vector<std::string>& warnings;
  std::string library_file;
  std::map<std::string, Material> library;
  std::map<std::string, int> index_of;  // material name -> index in room.materials

  bool known(const std::string& name) const { return index_of.count(name) || library.count(name); }

  // A material reference: a name in the scene's "materials", else in the library.
  int resolve(const JsonField& ref) {
    const std::string name = ref.string();
    if (const auto it = index_of.find(name); it != index_of.end()) return it->second;
    if (const auto it = library.find(name); it != library.end()) return add(it->second);
    ref.fail("undefined material " + inQuotes(name) + " (not in \"materials\"" +
             (library_file.empty() ? "; no materials_library is given)" : " nor in " + library_file + ")"));
  }

  int add(Material m) {
    const std::string name = m.name;
    const int i = room.addMaterial(std::move(m));
    index_of[name] = i;
    return i;
  }

  void materials(const JsonField& list) {
    for (const std::string& name : list.keys()) {
      const JsonField m = list[name];
      if (m.json().is_string()) {
        const std::string entry = m.string();
        const auto it = library.find(entry);
        if (it == library.end())
          m.fail("no material " + inQuotes(entry) + (library_file.empty() ? " (no materials_library is given)"
                                                                        : " in " + library_file));
        Material copy = it->second;
        copy.name = name;
        add(std::move(copy));
      } else {
        add(parseMaterial(m, name, room.bands));
      }
    }
  }

  void box(const JsonField& b, const std::string& fallback_name) {
    b.allowKeys({"name", "min", "max", "materials"});
    const std::string name = b.has("name") ? b["name"].string() : fallback_name;
    const core::Vec3 lo = b["min"].vec3(), hi = b["max"].vec3();
    for (int i = 0; i < 3; ++i)
      if (!(hi[i] > lo[i])) b["max"].fail("must exceed \"min\" in every coordinate");
    const JsonField mats = b["materials"];
    mats.allowKeys({"all", "walls", "x-", "x+", "y-", "y+", "floor", "ceiling"});
    static const char* wall_key[6] = {"x-", "x+", "y-", "y+", "floor", "ceiling"};
    int material_of_wall[6];
    for (int w = 0; w < 6; ++w) {
      const char* key = mats.has(wall_key[w]) ? wall_key[w]
                        : (w < 4 && mats.has("walls")) ? "walls"
                        : mats.has("all")              ? "all"
                                                       : nullptr;
      if (!key)
        mats.fail(std::string("no material for ") + wall_key[w] + " (give " + inQuotes(wall_key[w]) +
                  (w < 4 ? ", \"walls\"" : "") + " or \"all\")");
      material_of_wall[w] = resolve(mats[key]);
    }
    room.addBox(lo, hi, material_of_wall, name);
  }

  void polygon(const JsonField& p, const std::string& fallback_name) {
    p.allowKeys({"name", "vertices", "material"});
    const std::string name = p.has("name") ? p["name"].string() : fallback_name;
    const JsonField v = p["vertices"];
    const std::size_t n = v.arraySize();
    if (n < 3) v.fail("a polygon needs at least 3 vertices, got " + std::to_string(n));
    std::vector<core::Vec3> vertices;
    for (std::size_t i = 0; i < n; ++i) vertices.push_back(v.at(i).vec3());
    const int material = resolve(p["material"]);
    try {
      room.addPolygon(vertices, material, name);
    } catch (const core::InputError& e) {
      // addPolygon names the group; name the field instead.
      std::string why = e.what();
      if (why.rfind(name + ": ", 0) == 0) why = why.substr(name.size() + 2);
      v.fail(why);
    }
  }

  void obj(const JsonField& o) {
    o.allowKeys({"file", "materials", "default_material"});
    const JsonField file_field = o["file"];
    const std::string path = joinPath(base_dir, file_field.string());
    requireInputFile(file_field, path, "the OBJ file");
    const ObjModel model = loadObj(path);
    room.input_files.push_back(path);
    if (model.faces.empty()) file_field.fail(path + " has no faces");
    std::map<std::string, int> group_index;
    std::string group_list;
    for (std::size_t g = 0; g < model.groups.size(); ++g) {
      group_index[model.groups[g]] = static_cast<int>(g);
      group_list += (g ? ", " : "") + model.groups[g];
    }
    std::vector<int> material_of_group(model.groups.size(), -1);
    if (o.has("materials")) {
      const JsonField map = o["materials"];
      for (const std::string& g : map.keys()) {
        const auto it = group_index.find(g);
        if (it == group_index.end())
          map[g].fail("no face group " + inQuotes(g) + " in " + path + " (its groups: " + group_list + ")");
        material_of_group[it->second] = resolve(map[g]);
      }
    }
    for (std::size_t g = 0; g < model.groups.size(); ++g) {
      if (material_of_group[g] >= 0) continue;
      if (known(model.groups[g])) {  // a group (or usemtl) named after a material uses it
        material_of_group[g] = resolve(JsonField(nlohmann::json(model.groups[g]), file, o.path()));
      } else if (o.has("default_material")) {
        material_of_group[g] = resolve(o["default_material"]);
      } else {
        o.fail("face group " + inQuotes(model.groups[g]) + " of " + path +
               " has no material (map it in \"materials\" or give \"default_material\")");
      }
    }
    const int skipped = addObjToRoom(model, material_of_group, room);
    if (skipped > 0)
      warnings.push_back(path + ": skipped " + std::to_string(skipped) + " face(s) of zero area");
  }

  void geometry(const JsonField& list) {
    const std::size_t n = list.arraySize();
    if (n == 0) list.fail("must not be empty");
    for (std::size_t i = 0; i < n; ++i) {
      const JsonField item = list.at(i);
      item.allowKeys({"box", "polygon", "obj"});
      if (item.json().size() != 1) item.fail("must hold exactly one of \"box\", \"polygon\", \"obj\"");
      const std::string fallback = "geometry[" + std::to_string(i) + "]";
      if (item.has("box")) box(item["box"], fallback);
      else if (item.has("polygon")) polygon(item["polygon"], fallback);
      else obj(item["obj"]);
    }
  }

  Directivity directivity(const JsonField& d) {
    Directivity out;
    if (d.json().is_string()) {
      out.pattern = d.string();
      out.a = directivityWeight(out.pattern);
      if (out.a < 0) d.fail("unknown pattern " + inQuotes(out.pattern) + patternList());
      return out;
    }
    d.allowKeys({"pattern", "a", "axis"});
    if (d.has("pattern") == d.has("a")) d.fail("give either \"pattern\" (a name) or \"a\" (a number in [0, 1])");
    if (d.has("pattern")) {
      out.pattern = d["pattern"].string();
      out.a = directivityWeight(out.pattern);
      if (out.a < 0) d["pattern"].fail("unknown pattern " + inQuotes(out.pattern) + patternList());
    } else {
      out.a = d["a"].numberIn(0.0, 1.0);
      out.pattern = "a=" + formatNumber(out.a);
    }
    if (d.has("axis")) {
      out.axis = d["axis"].vec3();
      if (!(out.axis.norm() > 0.0)) d["axis"].fail("must not be the zero vector");
      out.axis.normalize();
    }
    return out;
  }

  static std::string patternList() {
    return " (one of omni, subcardioid, cardioid, supercardioid, hypercardioid, dipole)";
  }

  void sources(const JsonField& list) {
    const std::size_t n = list.arraySize();
    if (n == 0) list.fail("at least one source is needed");
    std::set<std::string> names;
    for (std::size_t i = 0; i < n; ++i) {
      const JsonField s = list.at(i);
      s.allowKeys({"name", "position", "power_w", "directivity"});
      Source src;
      src.name = s.has("name") ? s["name"].string() : "S" + std::to_string(i + 1);
      claimName(names, src.name, s, "source");
      src.position_m = s["position"].vec3();
      if (s.has("power_w")) src.power_w = s["power_w"].positive();
      if (s.has("directivity")) src.directivity = directivity(s["directivity"]);
      room.sources.push_back(src);
    }
  }

  void listeners(const JsonField& list) {
    const std::size_t n = list.arraySize();
    if (n == 0) list.fail("at least one listener is needed");
    std::set<std::string> names;
    for (std::size_t i = 0; i < n; ++i) {
      const JsonField l = list.at(i);
      l.allowKeys({"name", "position", "radius_m", "orientation", "look_at"});
      Listener r;
      r.name = l.has("name") ? l["name"].string() : "R" + std::to_string(i + 1);
      claimName(names, r.name, l, "listener");
      r.position_m = l["position"].vec3();
      if (l.has("radius_m")) r.radius_m = l["radius_m"].length();
      orientation(l, r);
      room.listeners.push_back(r);
    }
  }

  // A listener's "orientation" {yaw_deg, pitch_deg, roll_deg} (each optional, default 0) or "look_at" [x, y, z].
  // Yaw turns the head to the left about +z, pitch raises the nose, roll tilts the head towards the right
  // shoulder: forward/left/up = Rz(yaw)·Ry(−pitch)·Rx(roll) applied to +x, +y, +z. "look_at" faces the point
  // with the head upright (left horizontal).
  static void orientation(const JsonField& l, Listener& r) {
    if (l.has("orientation") && l.has("look_at")) l.fail("give either \"orientation\" or \"look_at\", not both");
    if (l.has("look_at")) {
      const Vec3 to = l["look_at"].vec3() - r.position_m;
      const double n = to.norm();
      if (!(n > 1e-9)) l["look_at"].fail("the point to look at is the listener's own position");
      r.forward = to / n;
      const Vec3 left = Vec3(0, 0, 1).cross(r.forward);
      if (!(left.norm() > 1e-6))
        l["look_at"].fail("looking straight up or down leaves the head's roll open: give \"orientation\" instead");
      r.left = left.normalized();
      r.up = r.forward.cross(r.left);
      return;
    }
    if (!l.has("orientation")) return;
    const JsonField o = l["orientation"];
    o.allowKeys({"yaw_deg", "pitch_deg", "roll_deg"});
    const double deg = core::kPi / 180.0;
    const double yaw = o.has("yaw_deg") ? o["yaw_deg"].numberIn(-360.0, 360.0) * deg : 0.0;
    const double pitch = o.has("pitch_deg") ? o["pitch_deg"].numberIn(-90.0, 90.0) * deg : 0.0;
    const double roll = o.has("roll_deg") ? o["roll_deg"].numberIn(-180.0, 180.0) * deg : 0.0;
    const double cy = std::cos(yaw), sy = std::sin(yaw), cp = std::cos(pitch), sp = std::sin(pitch);
    const double cr = std::cos(roll), sr = std::sin(roll);
    // Columns of Rz(yaw)·Ry(−pitch)·Rx(roll).
    r.forward = Vec3(cy * cp, sy * cp, sp);
    r.left = Vec3(-sy * cr - cy * sp * sr, cy * cr - sy * sp * sr, cp * sr);
    r.up = Vec3(sy * sr - cy * sp * cr, -cy * sr - sy * sp * cr, cp * cr);
  }

  void air(const JsonField& a) {
    a.allowKeys({"temperature_c", "humidity_percent", "pressure_kpa", "speed_of_sound_m_s"});
    // The validity range of ISO 9613-1's air absorption (−20…50 °C, up to 200 kPa).
    if (a.has("temperature_c")) room.air.temperature_c = a["temperature_c"].numberIn(-20.0, 50.0);
    if (a.has("humidity_percent")) room.air.humidity_percent = a["humidity_percent"].numberIn(0.0, 100.0);
    if (a.has("pressure_kpa")) room.air.pressure_kpa = a["pressure_kpa"].numberIn(50.0, 200.0);
    // Air from −50 to +125 °C; the temperature still sets the air absorption.
    if (a.has("speed_of_sound_m_s")) room.air.speed_of_sound_m_s = a["speed_of_sound_m_s"].numberIn(250.0, 450.0);
    if (room.air.humidity_percent < 10.0)
      warnings.push_back(a.where() + ": humidity below 10 % is outside ISO 9613-1's stated range");
  }

  void output(const JsonField& o) {
    o.allowKeys({"sample_rate_hz", "ir_length_s", "max_length_s", "histogram_bin_s", "ism_order", "rays", "seed"});
    Output& out = room.output;
    if (o.has("sample_rate_hz")) {
      const JsonField rate = o["sample_rate_hz"];
      out.sample_rate_hz = static_cast<double>(rate.integerIn(8000, 384000));
      // The IR's band filters need the top band and its crossover below the Nyquist frequency: ir::BandFilter's
      // transition of 40 Hz (half-width h with e·sinh(h·ln10) = 20 Hz) ends at e·10^h = 20 + √(e² + 20²) Hz.
      // For octaves up to 8 kHz, and third-octaves up to 10 kHz (e = 11220 Hz), the rate must exceed 22480 Hz.
      const int top = room.bands.size() - 1;
      const double edge_hz = room.bands.upperHz(top), half_hz = kTopCrossoverHalfWidthHz;
      const double highest_hz = half_hz + std::sqrt(edge_hz * edge_hz + half_hz * half_hz);
      if (!(highest_hz < 0.5 * out.sample_rate_hz))
        rate.fail("must exceed " + formatNumber(std::floor(2.0 * highest_hz)) + " Hz: the " + room.bands.label(top) +
                  " Hz band (up to " + formatNumber(std::round(room.bands.upperHz(top))) +
                  " Hz) must lie below the Nyquist frequency, got " + formatNumber(out.sample_rate_hz));
    }
    if (o.has("max_length_s")) out.max_length_s = o["max_length_s"].numberIn(1e-3, 600.0);
    if (o.has("ir_length_s")) {
      const JsonField len = o["ir_length_s"];
      if (len.json().is_string()) {
        if (len.string() != "auto") len.fail("must be \"auto\" or a length in seconds, got " + describeJson(len.json()));
        out.ir_length_s = 0.0;
      } else {
        out.ir_length_s = len.positive();
        if (out.ir_length_s > out.max_length_s)
          len.fail("must not exceed max_length_s (" + formatNumber(out.max_length_s) + "), got " +
                   formatNumber(out.ir_length_s));
      }
    }
    if (o.has("histogram_bin_s")) {
      out.histogram_bin_s = o["histogram_bin_s"].positive();
      if (out.histogram_bin_s > 0.001) o["histogram_bin_s"].fail("must be in (0, 0.001], got " + formatNumber(out.histogram_bin_s));
    }
    if (o.has("ism_order")) out.ism_order = static_cast<int>(o["ism_order"].integerIn(0, 50));
    if (o.has("rays")) out.rays = static_cast<std::uint64_t>(o["rays"].integerIn(1, 1000000000000));
    if (o.has("seed")) out.seed = static_cast<std::uint64_t>(o["seed"].integerIn(0, 9007199254740992));
  }
};

std::string folderOf(const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? "." : path.substr(0, slash);
}

std::string stemOf(const std::string& path) {
  std::string name = path.substr(path.find_last_of('/') + 1);
  if (const std::size_t dot = name.rfind('.'); dot != std::string::npos && dot > 0) name.resize(dot);
  return name;
}

}  // namespace

double directivityWeight(const std::string& pattern) {
  static const std::map<std::string, double> a = {{"omni", 1.0},          {"subcardioid", 0.7},
                                                  {"cardioid", 0.5},      {"supercardioid", 0.37},
                                                  {"hypercardioid", 0.25}, {"dipole", 0.0}};
  const auto it = a.find(pattern);
  return it == a.end() ? -1.0 : it->second;
}

Room parseRoom(const std::string& text, const std::string& file, const std::string& base_dir,
               std::vector<std::string>* warnings) {
  const nlohmann::json doc = parseJsonText(text, file);
  const JsonField top(doc, file);
  top.allowKeys({"name", "description", "bands", "materials_library", "materials", "geometry", "sources",
                 "listeners", "occluders", "air", "output"});
  std::vector<std::string> local_warnings;
  Room room;
  room.file = file;
  room.name = top.has("name") ? top["name"].string() : stemOf(file);
  if (top.has("description") && !top["description"].json().is_string())  // free text, may be empty
    top["description"].fail("must be a string, got " + describeJson(top["description"].json()));
  if (top.has("bands")) {
    const std::string b = top["bands"].string();
    if (b == "octave") room.bands = core::Bands::octave();
    else if (b == "third-octave") room.bands = core::Bands::thirdOctave();
    else top["bands"].fail("must be \"octave\" or \"third-octave\", got " + inQuotes(b));
  }
  if (!file.empty()) room.input_files.push_back(file);
  SceneParser p{file, base_dir, room, local_warnings, {}, {}, {}};
  if (top.has("materials_library")) {
    const JsonField lib = top["materials_library"];
    p.library_file = joinPath(base_dir, lib.string());
    requireInputFile(lib, p.library_file, "the material library");
    p.library = loadMaterialLibrary(p.library_file, room.bands);
    room.input_files.push_back(p.library_file);
  }
  if (top.has("materials")) p.materials(top["materials"]);
  // Occluders can bring their own surfaces (a barrier's panel): geometry is then optional (free field).
  if (top.has("geometry")) p.geometry(top["geometry"]);
  else if (!top.has("occluders"))
    throw core::InputError(file, "geometry: missing (required, unless occluders such as a barrier bring their own "
                                 "surfaces)");
  p.sources(top["sources"]);
  p.listeners(top["listeners"]);
  if (top.has("occluders"))
    parseOccluders(top["occluders"], room, [&p](const JsonField& ref) { return p.resolve(ref); }, local_warnings);
  if (top.has("air")) p.air(top["air"]);
  if (top.has("output")) p.output(top["output"]);
  if (warnings) {
    for (const std::string& w : roomWarnings(room)) local_warnings.push_back(file + ": " + w);
    warnings->insert(warnings->end(), local_warnings.begin(), local_warnings.end());
  }
  return room;
}

Room loadRoom(const std::string& path, std::vector<std::string>* warnings) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw core::InputError(path, "cannot open the scene file");
  std::ostringstream text;
  text << in.rdbuf();
  return parseRoom(text.str(), path, folderOf(path), warnings);
}

}  // namespace diffray::room
