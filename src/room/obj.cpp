#include "diffray/room/obj.h"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>

#include "diffray/core/error.h"
#include "diffray/core/number.h"
#include "diffray/room/json_fields.h"

namespace diffray::room {
namespace {

[[noreturn]] void fail(const std::string& file, int line, const std::string& what) {
  throw core::InputError(file + ":" + std::to_string(line), what);
}

// A vertex reference "7", "7/2", "7/2/3", "7//3" or "-1"; returns the 0-based index.
int parseIndex(const std::string& token, int vertex_count, const std::string& file, int line) {
  const std::string head = token.substr(0, token.find('/'));
  std::size_t used = 0;
  long i = 0;
  try {
    i = std::stol(head, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (head.empty() || used != head.size()) fail(file, line, "bad vertex reference \"" + token + "\"");
  const long index = i > 0 ? i - 1 : vertex_count + i;  // OBJ counts from 1; negative is relative
  if (i == 0 || index < 0 || index >= vertex_count)
    fail(file, line, "vertex index " + std::to_string(i) + " out of range (" + std::to_string(vertex_count) +
                         " vertices defined so far)");
  return static_cast<int>(index);
}

// Newell's normal of a polygon: its length is twice the polygon's area.
core::Vec3 newellNormal(const std::vector<core::Vec3>& p) {
  core::Vec3 n(0, 0, 0);
  for (std::size_t i = 0; i < p.size(); ++i) n += p[i].cross(p[(i + 1) % p.size()]);
  return n;
}

}  // namespace

ObjModel parseObj(std::istream& in, const std::string& file) {
  static const std::set<std::string> ignored = {"vt", "vn", "vp", "s", "mtllib", "l", "p", "lod", "usemap",
                                                "maplib", "shadow_obj", "trace_obj", "bevel", "c_interp",
                                                "d_interp", "cstype", "deg"};
  ObjModel m;
  m.file = file;
  std::string group_name, material_name;
  int current_group = -1;
  std::string current_key;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    if (const std::size_t hash = text.find('#'); hash != std::string::npos) text.resize(hash);
    std::istringstream s(text);
    std::string word;
    if (!(s >> word)) continue;
    if (word == "v") {
      double xyz[3];
      for (double& c : xyz) {
        std::string t;
        if (!(s >> t)) fail(file, line, "a vertex needs 3 coordinates");
        if (!core::parseDecimal(t, c)) fail(file, line, "bad coordinate \"" + t + "\"");
        if (!std::isfinite(c)) fail(file, line, "coordinate \"" + t + "\" is not finite");
        if (std::abs(c) > kMaxCoordinateM)
          fail(file, line, "coordinate \"" + t + "\" is beyond ±1e6 m (scenes are in float metres)");
      }
      m.vertices.emplace_back(xyz[0], xyz[1], xyz[2]);
    } else if (word == "f") {
      ObjFace f;
      f.line = line;
      for (std::string t; s >> t;) f.vertices.push_back(parseIndex(t, static_cast<int>(m.vertices.size()), file, line));
      if (f.vertices.size() < 3) fail(file, line, "a face needs at least 3 vertices");
      const std::string key = material_name.empty() ? (group_name.empty() ? "default" : group_name) : material_name;
      if (current_group < 0 || key != current_key) {
        current_key = key;
        current_group = -1;
        for (std::size_t g = 0; g < m.groups.size(); ++g)
          if (m.groups[g] == key) current_group = static_cast<int>(g);
        if (current_group < 0) {
          m.groups.push_back(key);
          current_group = static_cast<int>(m.groups.size()) - 1;
        }
      }
      f.group = current_group;
      m.faces.push_back(std::move(f));
    } else if (word == "g" || word == "o" || word == "usemtl") {
      std::string name, part;
      while (s >> part) name += (name.empty() ? "" : " ") + part;
      if (word == "usemtl") {
        if (name.empty()) fail(file, line, "usemtl needs a name");
        material_name = name;
      } else {
        group_name = name;
      }
    } else if (!ignored.count(word)) {
      fail(file, line, "unknown OBJ statement \"" + word + "\"");
    }
  }
  return m;
}

ObjModel loadObj(const std::string& path) {
  if (const std::string why = notRegularFile(path); !why.empty()) throw core::InputError(path, why);
  std::ifstream in(path);
  if (!in) throw core::InputError(path, "cannot open the OBJ file");
  return parseObj(in, path);
}

int addObjToRoom(const ObjModel& model, const std::vector<int>& material_of_group, Room& room) {
  DIFFRAY_CHECK(material_of_group.size() == model.groups.size());
  const int base = static_cast<int>(room.mesh.vertices.size());
  room.mesh.vertices.insert(room.mesh.vertices.end(), model.vertices.begin(), model.vertices.end());
  int skipped = 0;
  for (const ObjFace& f : model.faces) {
    std::vector<core::Vec3> p;
    double extent2 = 0.0;
    for (int v : f.vertices) p.push_back(model.vertices[v]);
    for (const auto& q : p) extent2 = std::max(extent2, (q - p[0]).squaredNorm());
    const core::Vec3 n = newellNormal(p);
    // Zero area relative to the face's size: collinear or repeated vertices.
    if (!(n.norm() > 1e-12 * extent2)) {
      ++skipped;
      continue;
    }
    const int material = material_of_group[f.group];
    const std::string& group = model.groups[f.group];
    // Convex: every corner turns the same way and the turns add up to one turn (2π), not more: a pentagram's
    // corners all turn the same way too, twice round. Anything else goes through addPolygon's checks.
    bool convex = true;
    double turning = 0.0;
    const core::Vec3 unit_n = n.normalized();
    for (std::size_t i = 0; i < p.size() && convex; ++i) {
      const core::Vec3 &a = p[i], &b = p[(i + 1) % p.size()], &c = p[(i + 2) % p.size()];
      const double sine = (b - a).cross(c - b).dot(unit_n);
      if (sine <= 0.0) convex = false;
      turning += std::atan2(sine, (b - a).dot(c - b));
    }
    if (convex && turning < 3.0 * core::kPi) {
      for (std::size_t i = 1; i + 1 < f.vertices.size(); ++i) {
        room.mesh.triangles.push_back({base + f.vertices[0], base + f.vertices[i], base + f.vertices[i + 1]});
        room.mesh.object_of_triangle.push_back(material);
        room.group_of_triangle.push_back(group);
      }
      continue;
    }
    try {
      room.addPolygon(p, material, group);
    } catch (const core::InputError& e) {
      fail(model.file, f.line, std::string(e.what()) + " (face of " + std::to_string(p.size()) + " vertices)");
    }
  }
  return skipped;
}

}  // namespace diffray::room
