// Scene files: the shipped rooms against the closed forms of their generator's dimensions and the
// published material tables; third-octave resampling against hand-computed values; one test per
// error path, checking that the single-line message names the file and the field.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>

#include "diffray/core/error.h"
#include "diffray/room/air.h"
#include "diffray/room/checks.h"
#include "diffray/room/materials.h"
#include "diffray/room/scene_file.h"
#include "temp_dir.h"

namespace dr = diffray::room;
namespace dc = diffray::core;

namespace {

const std::string kRooms = std::string(DIFFRAY_SOURCE_DIR) + "/rooms/";
const std::string kData = std::string(DIFFRAY_SOURCE_DIR) + "/tests/data/rooms";

// Index of the material named `name` used by the triangles of `group`; fails if they disagree.
std::string materialOfGroup(const dr::Room& room, const std::string& group) {
  std::set<int> m;
  for (std::size_t i = 0; i < room.group_of_triangle.size(); ++i)
    if (room.group_of_triangle[i] == group) m.insert(room.mesh.object_of_triangle[i]);
  EXPECT_EQ(m.size(), 1u) << group;
  return m.empty() ? "" : room.materials[*m.begin()].name;
}

void expectOctaves(const dc::BandArray& got, const std::vector<double>& want, const std::string& what) {
  for (std::size_t b = 0; b < want.size(); ++b) EXPECT_DOUBLE_EQ(got[b], want[b]) << what << " band " << b;
}

// Counts "f" lines of an OBJ file and the vertices of each: an independent count of triangles.
int objTriangleCount(const std::string& path) {
  std::ifstream in(path);
  int tris = 0;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("f ", 0) != 0) continue;
    int n = 0;
    for (std::size_t i = 1; i < line.size(); ++i)
      if (line[i] != ' ' && line[i - 1] == ' ') ++n;
    tris += n - 2;
  }
  return tris;
}

// A minimal valid scene, to break one field at a time.
nlohmann::json baseScene() {
  return nlohmann::json::parse(R"({
    "materials": {"m": {"absorption": 0.1, "scattering": 0.2}},
    "geometry": [{"box": {"min": [0, 0, 0], "max": [4, 3, 2.5], "materials": {"all": "m"}}}],
    "sources": [{"position": [1, 1, 1]}],
    "listeners": [{"position": [3, 2, 1.2]}]})");
}

std::string errorOfText(const std::string& text, const std::string& file = "rooms/x.json") {
  try {
    dr::parseRoom(text, file, kData);
  } catch (const dc::InputError& e) {
    return e.what();
  }
  return "(no error)";
}
std::string errorOf(const nlohmann::json& scene) { return errorOfText(scene.dump()); }

// The message is one line and holds every expected piece.
void expectMessage(const std::string& msg, std::initializer_list<const char*> pieces) {
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  for (const char* p : pieces) EXPECT_NE(msg.find(p), std::string::npos) << "missing \"" << p << "\" in: " << msg;
}

}  // namespace

TEST(RoomSceneFile, ShoeboxMatchesItsDimensionsAndTheLibrary) {
  std::vector<std::string> warnings;
  const dr::Room room = dr::loadRoom(kRooms + "shoebox.json", &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings[0];
  EXPECT_EQ(room.name, "shoebox");
  EXPECT_EQ(room.mesh.triangles.size(), 12u);
  EXPECT_NEAR(room.volume(), 10.0 * 7.0 * 3.0, 1e-9);
  EXPECT_NEAR(room.surfaceArea(), 2.0 * (10 * 7 + 10 * 3 + 7 * 3), 1e-9);
  ASSERT_EQ(room.bands.size(), 8);
  // Vorländer's annex, "Walls, hard surfaces average" and "6 mm pile carpet bonded to closed-cell foam
  // underlay", 125 Hz … 8 kHz, with 63 Hz = 125 Hz.
  EXPECT_EQ(materialOfGroup(room, "room/x-"), "walls");
  expectOctaves(room.materials[room.mesh.object_of_triangle[0]].absorption,
                {0.02, 0.02, 0.02, 0.03, 0.03, 0.04, 0.05, 0.05}, "walls");
  EXPECT_EQ(materialOfGroup(room, "room/floor"), "floor");
  for (const auto& m : room.materials)
    if (m.name == "floor") expectOctaves(m.absorption, {0.03, 0.03, 0.09, 0.25, 0.31, 0.33, 0.44, 0.44}, "floor");
  EXPECT_EQ(materialOfGroup(room, "room/ceiling"), "ceiling");
  ASSERT_EQ(room.sources.size(), 1u);
  EXPECT_EQ(room.listeners.size(), 2u);
  EXPECT_EQ(room.output.ir_length_s, 0.0);  // "auto"
  EXPECT_EQ(room.output.ism_order, 3);
}

TEST(RoomSceneFile, LHallMatchesItsGenerator) {
  std::vector<std::string> warnings;
  const dr::Room room = dr::loadRoom(kRooms + "l-hall.json", &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings[0];
  const int tris = objTriangleCount(kRooms + "l-hall.obj");
  EXPECT_GE(tris, 1000);
  EXPECT_EQ(static_cast<int>(room.mesh.triangles.size()), tris);
  // make_rooms.py: L of 24x12 + 12x12 m, 7 m high, minus a 6x12x1 m stage and four 0.5x0.5 m columns.
  EXPECT_NEAR(room.volume(), 432.0 * 7.0 - 6.0 * 12.0 * 1.0 - 4 * 0.25 * 7.0, 1e-9 * 3000);
  EXPECT_EQ(materialOfGroup(room, "seating"), "seats-upholstered-empty");
  EXPECT_EQ(materialOfGroup(room, "rear-wall"), "mineral-wool-panel");
  EXPECT_EQ(materialOfGroup(room, "columns"), "concrete-rough");
  EXPECT_EQ(materialOfGroup(room, "stage-floor"), "stage-floor");
  EXPECT_EQ(room.sources[0].directivity.a, 0.5);
  EXPECT_DOUBLE_EQ(room.sources[0].directivity.axis.x(), -1.0);
}

TEST(RoomSceneFile, TwoRoomsHaveANamedDoorway) {
  std::vector<std::string> warnings;
  const dr::Room room = dr::loadRoom(kRooms + "two-rooms.json", &warnings);
  EXPECT_TRUE(warnings.empty()) << warnings[0];
  EXPECT_EQ(static_cast<int>(room.mesh.triangles.size()), objTriangleCount(kRooms + "two-rooms.obj"));
  // Room A 6x5x3, room B 4x4x3, the 0.2 m deep doorway 0.9 x 2.1 m; the opening bounds nothing.
  EXPECT_NEAR(room.volume(), 90.0 + 48.0 + 0.2 * 0.9 * 2.1, 1e-9 * 140);
  EXPECT_EQ(dr::openEdgeCount(room), 0);
  int doorway = 0;
  for (std::size_t i = 0; i < room.mesh.triangles.size(); ++i) {
    if (room.group_of_triangle[i] != "doorway") continue;
    ++doorway;
    EXPECT_TRUE(room.isOpening(room.mesh.object_of_triangle[i]));
    for (int v : room.mesh.triangles[i]) {
      const auto& p = room.mesh.vertices[v];
      EXPECT_DOUBLE_EQ(p.x(), 6.1);
      EXPECT_TRUE(p.y() == 1.0 || p.y() == 1.9) << p.y();
      EXPECT_TRUE(p.z() == 0.0 || p.z() == 2.1) << p.z();
    }
  }
  EXPECT_EQ(doorway, 2);
  EXPECT_EQ(room.listeners.size(), 3u);
}

TEST(RoomMaterialLibrary, EntriesParseWithSources) {
  const auto lib = dr::loadMaterialLibrary(kRooms + "materials.json", dc::Bands::octave());
  EXPECT_GE(lib.size(), 15u);
  EXPECT_LE(lib.size(), 25u);
  for (const auto& [name, m] : lib) EXPECT_FALSE(m.reference.empty()) << name;
  // Published table values (Vorländer 2008 annex, 125 Hz … 8 kHz; 63 Hz = 125 Hz).
  expectOctaves(lib.at("curtain-heavy").absorption, {0.30, 0.30, 0.45, 0.65, 0.56, 0.59, 0.71, 0.71}, "curtain");
  // Entries that stop at 4 kHz repeat it at 8 kHz, and say so.
  expectOctaves(lib.at("acoustic-ceiling-tile").absorption, {0.49, 0.49, 0.53, 0.53, 0.75, 0.92, 0.99, 0.99}, "tile");
  EXPECT_NE(lib.at("acoustic-ceiling-tile").reference.find("8 kHz ESTIMATED"), std::string::npos);
  expectOctaves(lib.at("audience-seated").scattering, {0.3, 0.3, 0.5, 0.6, 0.6, 0.7, 0.7, 0.7}, "audience");
  const auto& door = lib.at("open-doorway");
  for (int b = 0; b < 8; ++b) EXPECT_EQ(door.transmission[b], 1.0);
}

TEST(RoomMaterials, ThirdOctavesInterpolateInLogFrequency) {
  auto scene = baseScene();
  scene["bands"] = "third-octave";
  scene["materials"]["m"]["absorption"] = {0.10, 0.40, 0.20, 0.50, 0.30, 0.60, 0.35, 0.90};
  const dr::Room room = dr::parseRoom(scene.dump(), "x.json", kData);
  ASSERT_EQ(room.bands.size(), 24);  // 50 Hz … 10 kHz
  const auto& a = room.materials[0].absorption;
  // Hand computed: a third-octave centre one third of the way (in log f) between two octave centres
  // takes 2/3 of the lower value and 1/3 of the upper; beyond 63 Hz and 8 kHz the end values hold.
  const std::map<double, double> want = {{50, 0.10},   {63, 0.10},   {80, 0.20},    {100, 0.30},
                                         {125, 0.40},  {160, 1.0 / 3}, {200, 4.0 / 15}, {4000, 0.35},
                                         {5000, 0.35 + 0.55 / 3}, {6300, 0.35 + 1.1 / 3}, {8000, 0.90}, {10000, 0.90}};
  for (const auto& [hz, v] : want) {
    const int b = room.bands.find(hz);
    ASSERT_GE(b, 0) << hz;
    EXPECT_NEAR(a[b], v, 1e-12) << hz << " Hz";
  }
}

TEST(RoomMaterials, TheThreeFormsOfABandValueAgree) {
  auto scene = baseScene();
  scene["materials"]["arr"] = {{"absorption", {0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8}}, {"scattering", 0.5}};
  scene["materials"]["obj"] = {{"absorption", {{"63", 0.1}, {"125", 0.2}, {"250", 0.3}, {"500", 0.4}, {"1000", 0.5},
                                               {"2000", 0.6}, {"4000", 0.7}, {"8000", 0.8}}},
                               {"scattering", {0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5, 0.5}}, {"transmission", 0.05}};
  const dr::Room room = dr::parseRoom(scene.dump(), "x.json", kData);
  const dr::Material *arr = nullptr, *obj = nullptr;
  for (const auto& m : room.materials) {
    if (m.name == "arr") arr = &m;
    if (m.name == "obj") obj = &m;
  }
  ASSERT_TRUE(arr && obj);
  for (int b = 0; b < 8; ++b) {
    EXPECT_DOUBLE_EQ(arr->absorption[b], 0.1 * (b + 1));
    EXPECT_EQ(arr->absorption[b], obj->absorption[b]);
    EXPECT_EQ(arr->scattering[b], obj->scattering[b]);
    EXPECT_EQ(obj->transmission[b], 0.05);
  }
}

TEST(RoomSceneFile, DefaultsAndDirectivity) {
  auto scene = baseScene();
  scene["sources"][0]["directivity"] = {{"a", 0.7}, {"axis", {0, 0, 2}}};
  scene["sources"].push_back({{"position", {2, 2, 1}}, {"directivity", "hypercardioid"}});
  const dr::Room room = dr::parseRoom(scene.dump(), "dir/x.json", kData);
  EXPECT_EQ(room.name, "x");
  EXPECT_EQ(room.sources[0].name, "S1");
  EXPECT_EQ(room.sources[1].name, "S2");
  EXPECT_EQ(room.sources[0].directivity.a, 0.7);
  EXPECT_DOUBLE_EQ(room.sources[0].directivity.axis.z(), 1.0);
  EXPECT_EQ(room.sources[1].directivity.a, 0.25);
  EXPECT_EQ(room.sources[0].power_w, 1.0);
  EXPECT_EQ(room.listeners[0].radius_m, 0.1);
  EXPECT_EQ(room.output.sample_rate_hz, 48000.0);
  EXPECT_EQ(room.output.rays, 1000000u);
  EXPECT_EQ(room.air.temperature_c, 20.0);
  EXPECT_EQ(dr::directivityWeight("supercardioid"), 0.37);
  EXPECT_EQ(dr::directivityWeight("subcardioid"), 0.7);
  EXPECT_EQ(dr::directivityWeight("dipole"), 0.0);
}

// ---- Bad input: one line naming the file, the field and what is wrong. ----

TEST(RoomSceneFileErrors, UnknownKeySuggestsTheKnownOne) {
  auto scene = baseScene();
  scene["materials"]["m"]["absorbtion"] = 0.1;
  expectMessage(errorOf(scene), {"rooms/x.json: materials.m.absorbtion: unknown key", "did you mean \"absorption\""});
  scene = baseScene();
  scene["listners"] = nlohmann::json::array();
  expectMessage(errorOf(scene), {"rooms/x.json: listners: unknown key", "\"listeners\""});
}

TEST(RoomSceneFileErrors, CoefficientOutOfRange) {
  auto scene = baseScene();
  scene["materials"]["carpet"] = {{"absorption", {0.1, 0.1, 0.1, 1.2, 0.1, 0.1, 0.1, 0.1}}, {"scattering", 0.1}};
  EXPECT_EQ(errorOf(scene), "rooms/x.json: materials.carpet.absorption[3]: must be in [0, 1], got 1.2");
  scene["materials"]["carpet"] = {{"absorption", 0.5}, {"scattering", -0.1}};
  expectMessage(errorOf(scene), {"rooms/x.json: materials.carpet.scattering: must be in [0, 1], got -0.1"});
  scene["materials"]["carpet"] = {{"absorption", 0.5}, {"scattering", {{"63", 0.1}}}};
  expectMessage(errorOf(scene), {"materials.carpet.scattering.125: missing"});
  scene["materials"]["carpet"] = {{"absorption", {0.1, 0.2}}, {"scattering", 0.1}};
  expectMessage(errorOf(scene), {"materials.carpet.absorption: must have 8 elements, got 2"});
}

TEST(RoomSceneFileErrors, TransmissionAboveAbsorption) {
  auto scene = baseScene();
  scene["materials"]["m"]["transmission"] = {0, 0, 0.2, 0, 0, 0, 0, 0};
  expectMessage(errorOf(scene), {"rooms/x.json: materials.m.transmission[2]: must not exceed the absorption",
                                 "250 Hz"});
}

TEST(RoomSceneFileErrors, NaNAndInfinity) {
  auto scene = baseScene();
  scene["sources"][0]["position"][1] = std::nan("");  // nlohmann writes NaN as null
  expectMessage(errorOf(scene), {"rooms/x.json: sources[0].position[1]: must be a number, got null"});
  // A literal NaN is not JSON: a syntax error with line and column.
  expectMessage(errorOfText("{\n  \"sources\": [{\"position\": [1, NaN, 1]}]\n}"), {"rooms/x.json:2:", "JSON syntax error"});
  // 1e999 overflows to infinity.
  std::string text = baseScene().dump();
  text.replace(text.find("2.5"), 3, "1e999");
  expectMessage(errorOfText(text), {"rooms/x.json: number overflow parsing '1e999' (numbers must be finite)"});
}

TEST(RoomSceneFileErrors, SyntaxErrorGivesLineAndColumn) {
  expectMessage(errorOfText("{\n  \"name\": \"x\",\n  \"bands\": ,\n}"), {"rooms/x.json:3:12: JSON syntax error"});
  // Comments are allowed.
  auto text = baseScene().dump();
  text.insert(1, "// a comment\n");
  EXPECT_EQ(errorOfText(text), "(no error)");
}

TEST(RoomSceneFileErrors, SourcesListenersAndTheirValues) {
  auto scene = baseScene();
  scene["listeners"][0]["radius_m"] = 0;
  EXPECT_EQ(errorOf(scene), "rooms/x.json: listeners[0].radius_m: must be > 0, got 0");
  scene = baseScene();
  scene["sources"][0]["power_w"] = -1;
  expectMessage(errorOf(scene), {"rooms/x.json: sources[0].power_w: must be > 0"});
  scene = baseScene();
  scene["sources"] = nlohmann::json::array();
  expectMessage(errorOf(scene), {"rooms/x.json: sources: at least one source"});
  scene = baseScene();
  scene.erase("listeners");
  expectMessage(errorOf(scene), {"rooms/x.json: listeners: missing (required)"});
  scene = baseScene();
  scene["sources"][0]["directivity"] = "cardiod";
  expectMessage(errorOf(scene), {"sources[0].directivity: unknown pattern \"cardiod\""});
  scene = baseScene();
  scene["sources"][0]["directivity"] = {{"a", 0.5}, {"axis", {0, 0, 0}}};
  expectMessage(errorOf(scene), {"sources[0].directivity.axis: must not be the zero vector"});
  scene = baseScene();
  scene["listeners"].push_back({{"name", "R1"}, {"position", {1, 1, 1}}});
  expectMessage(errorOf(scene), {"listeners[1].name: duplicate listener name"});
}

TEST(RoomSceneFileErrors, OutputRanges) {
  const std::vector<std::pair<std::string, nlohmann::json>> bad = {
      {"sample_rate_hz", 1000}, {"sample_rate_hz", 500000}, {"histogram_bin_s", 0.002}, {"histogram_bin_s", 0},
      {"ism_order", 51},        {"ism_order", 2.5},         {"ism_order", -1},         {"rays", 0},
      {"ir_length_s", "long"},  {"ir_length_s", 20}};
  for (const auto& [key, value] : bad) {
    auto scene = baseScene();
    scene["output"][key] = value;
    expectMessage(errorOf(scene), {"rooms/x.json: output.", key.c_str()});
  }
  auto scene = baseScene();
  scene["air"] = {{"humidity_percent", 120}};
  expectMessage(errorOf(scene), {"rooms/x.json: air.humidity_percent: must be in [0, 100], got 120"});
  scene = baseScene();
  scene["bands"] = "octaves";
  expectMessage(errorOf(scene), {"rooms/x.json: bands: must be \"octave\" or \"third-octave\""});
}

TEST(RoomSceneFile, EveryAirTheFileAcceptsTheAirModelAccepts) {
  // The scene file and room/air.h check the air separately; a value the file accepts must not fail later,
  // after the trace, in the air model (pressure_kpa 150 used to pass the file and fail air.pressure).
  for (const auto& air : {nlohmann::json{{"temperature_c", -20}, {"humidity_percent", 0}, {"pressure_kpa", 50}},
                          nlohmann::json{{"temperature_c", 50}, {"humidity_percent", 100}, {"pressure_kpa", 200}},
                          nlohmann::json{{"pressure_kpa", 150}}}) {
    auto scene = baseScene();
    scene["air"] = air;
    const dr::Room room = dr::parseRoom(scene.dump(), "rooms/x.json", kData);
    EXPECT_NO_THROW(dr::airAttenuationPerM(room.air, room.bands)) << air.dump();
    EXPECT_NO_THROW(dr::speedOfSound(room.air)) << air.dump();
  }
}

TEST(RoomSceneFile, TheSpeedOfSoundCanBeGivenDirectly) {
  auto scene = baseScene();
  scene["air"] = {{"temperature_c", 10}, {"speed_of_sound_m_s", 343}};
  const dr::Room room = dr::parseRoom(scene.dump(), "rooms/x.json", kData);
  EXPECT_EQ(dr::speedOfSound(room.air), 343.0);
  // The temperature alone: 331.3·√(1 + T/273.15) (the textbook formula, written here).
  scene["air"] = {{"temperature_c", 10}};
  EXPECT_NEAR(dr::speedOfSound(dr::parseRoom(scene.dump(), "rooms/x.json", kData).air), 331.3 * std::sqrt(1.0 + 10.0 / 273.15), 1e-12);
  scene["air"] = {{"speed_of_sound_m_s", 1500}};
  expectMessage(errorOf(scene), {"rooms/x.json: air.speed_of_sound_m_s:", "450"});
}

TEST(RoomSceneFileErrors, UndefinedMaterial) {
  auto scene = baseScene();
  scene["geometry"][0]["box"]["materials"] = {{"all", "m"}, {"floor", "nope"}};
  expectMessage(errorOf(scene), {"rooms/x.json: geometry[0].box.materials.floor: undefined material \"nope\""});
  scene = baseScene();
  scene["geometry"][0]["box"]["materials"] = {{"walls", "m"}};
  expectMessage(errorOf(scene), {"geometry[0].box.materials: no material for floor"});
  scene = baseScene();
  scene["materials"]["alias"] = "not-in-library";
  expectMessage(errorOf(scene), {"rooms/x.json: materials.alias: no material \"not-in-library\""});
  scene = baseScene();
  scene["materials_library"] = "missing.json";
  expectMessage(errorOf(scene), {"rooms/x.json: materials_library: cannot open"});
}

TEST(RoomSceneFileErrors, Geometry) {
  auto scene = baseScene();
  scene["geometry"][0]["box"]["max"] = {4, 0, 2.5};
  expectMessage(errorOf(scene), {"geometry[0].box.max: must exceed \"min\""});
  scene = baseScene();
  scene["geometry"].push_back({{"polygon", {{"vertices", {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}}, {"material", "m"}}}});
  expectMessage(errorOf(scene), {"rooms/x.json: geometry[1].polygon.vertices:", "no area"});
  scene = baseScene();
  scene["geometry"].push_back({{"box", scene["geometry"][0]["box"]}, {"obj", {{"file", "a.obj"}}}});
  expectMessage(errorOf(scene), {"geometry[1]: must hold exactly one of"});
}

TEST(RoomSceneFileErrors, ObjFiles) {
  auto scene = baseScene();
  scene["geometry"] = {{{"obj", {{"file", "missing.obj"}, {"default_material", "m"}}}}};
  expectMessage(errorOf(scene), {"rooms/x.json: geometry[0].obj.file: cannot open the OBJ file", "missing.obj"});
  scene["geometry"][0]["obj"]["file"] = "bad-index.obj";
  expectMessage(errorOf(scene), {"bad-index.obj:4: vertex index 9 out of range (3 vertices"});
  scene["geometry"][0]["obj"] = {{"file", "cube.obj"}};
  expectMessage(errorOf(scene), {"geometry[0].obj: face group \"top\"", "has no material"});
  scene["geometry"][0]["obj"] = {{"file", "cube.obj"}, {"materials", {{"tops", "m"}}}, {"default_material", "m"}};
  expectMessage(errorOf(scene), {"geometry[0].obj.materials.tops: no face group \"tops\"", "top, bottom, sides"});
}

TEST(RoomSceneFile, DegenerateObjFacesAreSkippedWithAWarning) {
  auto scene = baseScene();
  scene["geometry"] = {{{"obj", {{"file", "cube.obj"}, {"default_material", "m"}}}}};
  scene["sources"][0]["position"] = {0.5, 0.5, 0.5};
  scene["listeners"][0]["position"] = {0.3, 0.7, 0.6};
  std::vector<std::string> warnings;
  const dr::Room room = dr::parseRoom(scene.dump(), "rooms/x.json", kData, &warnings);
  EXPECT_EQ(room.mesh.triangles.size(), 12u);
  EXPECT_NEAR(room.volume(), 1.0, 1e-12);
  ASSERT_EQ(warnings.size(), 1u);
  expectMessage(warnings[0], {"cube.obj: skipped 2 face(s) of zero area"});
}

TEST(RoomSceneFileErrors, ADefaultNameClashIsADuplicateOnTheEntry) {
  // The second source's default name is "S2", which the first one took: the entry has no "name" to blame.
  auto scene = baseScene();
  scene["sources"] = {{{"name", "S2"}, {"position", {1, 1, 1}}}, {{"position", {2, 1, 1}}}};
  EXPECT_EQ(errorOf(scene), "rooms/x.json: sources[1]: duplicate source name \"S2\"");
  scene = baseScene();
  scene["listeners"] = {{{"name", "R2"}, {"position", {3, 2, 1.2}}}, {{"position", {3, 1, 1.2}}}};
  EXPECT_EQ(errorOf(scene), "rooms/x.json: listeners[1]: duplicate listener name \"R2\"");
  // A given name that clashes is still blamed on the name.
  scene = baseScene();
  scene["sources"] = {{{"position", {1, 1, 1}}}, {{"name", "S1"}, {"position", {2, 1, 1}}}};
  EXPECT_EQ(errorOf(scene), "rooms/x.json: sources[1].name: duplicate source name \"S1\"");
}

TEST(RoomSceneFileErrors, NamesThatWouldBreakTheHistogramCsv) {
  for (const char* name : {"R,1", "R\"1", "R\n1"}) {
    auto scene = baseScene();
    scene["listeners"][0]["name"] = name;
    expectMessage(errorOf(scene), {"rooms/x.json: listeners[0].name: listener name", "must not contain a comma"});
    scene = baseScene();
    scene["sources"][0]["name"] = name;
    expectMessage(errorOf(scene), {"rooms/x.json: sources[0].name: source name", "must not contain a comma"});
  }
}

TEST(RoomSceneFile, AnEmptyDescriptionIsFreeText) {
  auto scene = baseScene();
  scene["description"] = "";
  EXPECT_EQ(errorOf(scene), "(no error)");
  scene["description"] = 3;
  EXPECT_EQ(errorOf(scene), "rooms/x.json: description: must be a string, got 3");
}

TEST(RoomSceneFileErrors, SampleRateIsWholeAndAboveTheTopBandsNyquist) {
  auto scene = baseScene();
  scene["output"]["sample_rate_hz"] = 44100.5;
  EXPECT_EQ(errorOf(scene), "rooms/x.json: output.sample_rate_hz: must be a whole number, got 44100.5");
  // Both band sets end at 10^4.05 Hz (8 kHz octave: 10^(3.9 + 0.15); 10 kHz third-octave: 10^(4 + 0.05)), and the
  // band filters' 40 Hz crossover (half-width h, e·sinh(h ln 10) = 20 Hz) ends at 20 + √(e² + 20²) Hz:
  // the rate must exceed twice that, 22480.40 Hz.
  const double e = std::pow(10.0, 4.05), lowest = 2.0 * (20.0 + std::sqrt(e * e + 400.0));
  ASSERT_NEAR(lowest, 22480.40, 0.01);
  for (const char* bands : {"octave", "third-octave"}) {
    scene = baseScene();
    scene["bands"] = bands;
    scene["output"]["sample_rate_hz"] = 16000;
    expectMessage(errorOf(scene), {"rooms/x.json: output.sample_rate_hz: must exceed 22480 Hz", "Nyquist"});
    scene["output"]["sample_rate_hz"] = std::floor(lowest);
    expectMessage(errorOf(scene), {"rooms/x.json: output.sample_rate_hz: must exceed 22480 Hz"});
    scene["output"]["sample_rate_hz"] = std::ceil(lowest);
    EXPECT_EQ(errorOf(scene), "(no error)") << bands;
  }
}

TEST(RoomSceneFileErrors, AKeyGivenTwiceInOneObject) {
  // nlohmann keeps the last of two equal keys; a scene refuses them, naming the path.
  const std::string materials = R"("materials": {"m": {"absorption": 0.1, "scattering": 0.1},
                                                 "m": {"absorption": 0.9, "scattering": 0.1}},)";
  const std::string rest = R"("geometry": [{"box": {"min": [0, 0, 0], "max": [4, 3, 2.5], "materials": {"all": "m"}}}],
                              "listeners": [{"position": [3, 2, 1.2]}])";
  EXPECT_EQ(errorOfText("{" + materials + rest + R"(, "sources": [{"position": [1, 1, 1]}]})"),
            "rooms/x.json: materials.m: duplicate key");
  EXPECT_EQ(errorOfText(R"({"materials": {"m": {"absorption": 0.1, "scattering": 0.1}},)" + rest +
                        R"(, "sources": [{"position": [1, 1, 1]}], "sources": [{"position": [2, 1, 1]}]})"),
            "rooms/x.json: sources: duplicate key");
  EXPECT_EQ(errorOfText(R"({"materials": {"m": {"absorption": 0.1, "scattering": 0.1}},)" + rest +
                        R"(, "sources": [{"position": [1, 1, 1]}, {"position": [2, 1, 1], "position": [2, 2, 1]}]})"),
            "rooms/x.json: sources[1].position: duplicate key");
  // Equal keys in different objects are fine (every source has its own "position").
  EXPECT_EQ(errorOfText(R"({"materials": {"m": {"absorption": 0.1, "scattering": 0.1}},)" + rest +
                        R"(, "sources": [{"position": [1, 1, 1]}, {"position": [2, 1, 1]}]})"),
            "(no error)");
  // The material library goes through the same parser.
  const diffray::test::TempDir dir("dup_library");
  const std::string lib = dir.file("library.json");
  std::ofstream(lib) << R"({"materials": {"a": {"absorption": 0.1, "scattering": 0.1, "source": "x"},
                                          "a": {"absorption": 0.2, "scattering": 0.1, "source": "x"}}})";
  try {
    dr::loadMaterialLibrary(lib, dc::Bands::octave());
    ADD_FAILURE() << "no error";
  } catch (const dc::InputError& err) {
    EXPECT_EQ(std::string(err.what()), lib + ": materials.a: duplicate key");
  }
}

TEST(RoomSceneFileErrors, NamedFilesMustBeRegularFiles) {
  auto scene = baseScene();
  scene["geometry"].push_back({{"obj", {{"file", "."}, {"default_material", "m"}}}});
  expectMessage(errorOf(scene), {"rooms/x.json: geometry[1].obj.file: ", "is a directory, not the OBJ file"});
  scene["geometry"][1]["obj"]["file"] = "/dev/null";
  expectMessage(errorOf(scene), {"rooms/x.json: geometry[1].obj.file: /dev/null is not a regular file"});
  scene["geometry"][1]["obj"]["file"] = "no-faces.obj";
  expectMessage(errorOf(scene), {"rooms/x.json: geometry[1].obj.file: ", "no-faces.obj has no faces"});
  scene = baseScene();
  scene["materials_library"] = ".";
  expectMessage(errorOf(scene), {"rooms/x.json: materials_library: ", "is a directory, not the material library"});
}

TEST(RoomSceneFileErrors, ABowTieIsSelfIntersectingNotArealess) {
  // Its two halves cancel in the area (Newell's normal is zero), but what is wrong is the crossing.
  auto scene = baseScene();
  scene["geometry"].push_back(
      {{"polygon", {{"vertices", {{1, 1, 1}, {2, 2, 1}, {2, 1, 1}, {1, 2, 1}}}, {"material", "m"}}}});
  expectMessage(errorOf(scene), {"rooms/x.json: geometry[1].polygon.vertices: the polygon is self-intersecting"});
}

// Every shipped room (rooms/*.json but the material library) loads: the README's commands keep working.
TEST(RoomShippedScenes, EveryRoomLoads) {
  int rooms = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kRooms)) {
    if (entry.path().extension() != ".json" || entry.path().filename() == "materials.json") continue;
    SCOPED_TRACE(entry.path().string());
    dr::Room room;
    EXPECT_NO_THROW(room = dr::loadRoom(entry.path().string()));
    EXPECT_FALSE(room.sources.empty());
    EXPECT_FALSE(room.listeners.empty());
    EXPECT_GT(room.mesh.triangleCount(), 0);
    ++rooms;
  }
  EXPECT_GE(rooms, 5);
}
