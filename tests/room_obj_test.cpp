// OBJ parsing: index forms, negative indices, groups (usemtl over g/o), ignored statements, polygon
// triangulation checked by area against closed forms, and errors naming FILE:LINE.
#include <gtest/gtest.h>

#include <sstream>

#include "diffray/core/error.h"
#include "diffray/room/obj.h"
#include "temp_dir.h"

namespace dr = diffray::room;
namespace dc = diffray::core;

namespace {

dr::ObjModel parse(const std::string& text) {
  std::istringstream in(text);
  return dr::parseObj(in, "t.obj");
}

std::string errorOf(const std::string& text) {
  try {
    parse(text);
  } catch (const dc::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

// The message loadObj(path) refuses the file with.
std::string loadErrorOf(const std::string& path) {
  try {
    dr::loadObj(path);
  } catch (const dc::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

dr::Room roomWith(const dr::ObjModel& m, int* skipped = nullptr) {
  dr::Room room;
  dr::Material mat;
  mat.name = "m";
  room.addMaterial(mat);
  const int s = dr::addObjToRoom(m, std::vector<int>(m.groups.size(), 0), room);
  if (skipped) *skipped = s;
  return room;
}

}  // namespace

TEST(RoomObj, IndexFormsAndNegativeIndices) {
  const auto m = parse(
      "# comment\nmtllib x.mtl\nv 0 0 0\nv 1 0 0 1.0\nv 1 1 0\nvt 0 0\nvn 0 0 1\ns off\n"
      "f 1/1/1 2/1/1 3/1/1\nf 1//1 2//1 3//1 # trailing comment\nf 1/1 2/1 3/1\nf -3 -2 -1\n");
  ASSERT_EQ(m.vertices.size(), 3u);
  ASSERT_EQ(m.faces.size(), 4u);
  for (const auto& f : m.faces) EXPECT_EQ(f.vertices, (std::vector<int>{0, 1, 2}));
  EXPECT_EQ(m.faces[3].line, 12);
  EXPECT_EQ(m.groups, (std::vector<std::string>{"default"}));
}

TEST(RoomObj, UsemtlWinsOverGroupNames) {
  const auto m = parse(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
      "f 1 2 3\n"            // default
      "o hall\nf 1 2 3\n"    // hall
      "g walls\nf 1 2 3\n"   // walls
      "usemtl plaster\nf 1 2 3\n"
      "g floor\nf 1 2 3\n"   // still plaster: usemtl persists and wins
      "usemtl wood panel\nf 1 2 3\n");
  EXPECT_EQ(m.groups, (std::vector<std::string>{"default", "hall", "walls", "plaster", "wood panel"}));
  const std::vector<int> want = {0, 1, 2, 3, 3, 4};
  for (std::size_t i = 0; i < want.size(); ++i) EXPECT_EQ(m.faces[i].group, want[i]) << i;
}

TEST(RoomObj, ConvexPolygonsAreFannedOnSharedVertices) {
  // A regular hexagon of circumradius 1: area 3√3/2.
  std::string text;
  for (int i = 0; i < 6; ++i)
    text += "v " + std::to_string(std::cos(i * M_PI / 3)) + " " + std::to_string(std::sin(i * M_PI / 3)) + " 0\n";
  text += "f 1 2 3 4 5 6\n";
  const dr::Room room = roomWith(parse(text));
  EXPECT_EQ(room.mesh.triangles.size(), 4u);
  EXPECT_EQ(room.mesh.vertices.size(), 6u);  // no copies
  EXPECT_NEAR(room.surfaceArea(), 1.5 * std::sqrt(3.0), 1e-5);  // to_string keeps 6 decimals
}

TEST(RoomObj, ConcavePolygonsAreEarClipped) {
  // An L: the 2x2 square minus its 1x1 top-right quarter, area 3, 6 vertices -> 4 triangles.
  const dr::Room room = roomWith(parse("v 0 0 0\nv 2 0 0\nv 2 1 0\nv 1 1 0\nv 1 2 0\nv 0 2 0\nf 1 2 3 4 5 6\n"));
  EXPECT_EQ(room.mesh.triangles.size(), 4u);
  EXPECT_NEAR(room.surfaceArea(), 3.0, 1e-12);
}

TEST(RoomObj, DegenerateFacesAreSkippedAndCounted) {
  int skipped = 0;
  const dr::Room room = roomWith(parse("v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\nf 1 1 4\n"), &skipped);
  EXPECT_EQ(skipped, 2);
  EXPECT_EQ(room.mesh.triangles.size(), 1u);
}

TEST(RoomObj, ErrorsNameFileAndLine) {
  EXPECT_EQ(errorOf("v 0 0 0\nv 1 0 0\nf 1 2 3\n"), "t.obj:3: vertex index 3 out of range (2 vertices defined so far)");
  EXPECT_EQ(errorOf("v 0 0 0\nf 0 1 1\n"), "t.obj:2: vertex index 0 out of range (1 vertices defined so far)");
  EXPECT_EQ(errorOf("v 0 0 0\nf -2 1 1\n"), "t.obj:2: vertex index -2 out of range (1 vertices defined so far)");
  EXPECT_EQ(errorOf("v 0 0\n"), "t.obj:1: a vertex needs 3 coordinates");
  EXPECT_EQ(errorOf("\n\nv 0 x 0\n"), "t.obj:3: bad coordinate \"x\"");
  // Decimal numbers only, as every option reads them: no hex float, and nan or inf is a word, not a number.
  EXPECT_EQ(errorOf("v 0 0 0x1p1\n"), "t.obj:1: bad coordinate \"0x1p1\"");
  EXPECT_EQ(errorOf("v 0 0 inf\n"), "t.obj:1: bad coordinate \"inf\"");
  EXPECT_EQ(errorOf("v nan 0 0\n"), "t.obj:1: bad coordinate \"nan\"");
  EXPECT_EQ(errorOf("v 0 0 1e999\n"), "t.obj:1: coordinate \"1e999\" is not finite");
  // Finite but beyond what Embree's float scene holds (it would assert inside rtcIntersect1).
  EXPECT_EQ(errorOf("v 0 0 2e6\n"), "t.obj:1: coordinate \"2e6\" is beyond ±1e6 m (scenes are in float metres)");
  EXPECT_EQ(errorOf("v 0 0 0\nv 1 0 0\nf 1 2\n"), "t.obj:3: a face needs at least 3 vertices");
  EXPECT_EQ(errorOf("v 0 0 0\nf a 1 1\n"), "t.obj:2: bad vertex reference \"a\"");
  EXPECT_EQ(errorOf("vx 0 0 0\n"), "t.obj:1: unknown OBJ statement \"vx\"");
  EXPECT_EQ(errorOf("usemtl\n"), "t.obj:1: usemtl needs a name");
  // A self-intersecting (bow-tie-like) concave face cannot be triangulated.
  const auto bow = parse("v 0 0 0\nv 2 0 0\nv 0 2 0\nv 2 2 0\nv 1 3 0\nf 1 2 3 4 5\n");
  try {
    roomWith(bow);
    ADD_FAILURE() << "no error";
  } catch (const dc::InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("t.obj:6: ", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("self-intersecting"), std::string::npos) << e.what();
  }
}

TEST(RoomObj, MissingFile) {
  EXPECT_EQ(loadErrorOf("/nonexistent/x.obj"), "/nonexistent/x.obj: cannot open the OBJ file");
}

TEST(RoomObj, AStarPolygonIsRefusedNotFanned) {
  // A pentagram {5/2}: every corner turns the same way, but twice round (total turning 4π). Fanned, it gave
  // overlapping triangles; it is self-intersecting, as the same polygon given inline in a scene is.
  std::string text;
  for (int i = 0; i < 5; ++i)
    text += "v " + std::to_string(std::cos(i * 4 * M_PI / 5)) + " " + std::to_string(std::sin(i * 4 * M_PI / 5)) + " 0\n";
  text += "f 1 2 3 4 5\n";
  try {
    roomWith(parse(text));
    ADD_FAILURE() << "no error";
  } catch (const dc::InputError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("t.obj:6: ", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("self-intersecting"), std::string::npos) << e.what();
  }
  // The convex pentagon on the same points is fanned: 3 triangles, area (5/2)·sin 72° for circumradius 1.
  text.clear();
  for (int i = 0; i < 5; ++i)
    text += "v " + std::to_string(std::cos(i * 2 * M_PI / 5)) + " " + std::to_string(std::sin(i * 2 * M_PI / 5)) + " 0\n";
  text += "f 1 2 3 4 5\n";
  const dr::Room room = roomWith(parse(text));
  EXPECT_EQ(room.mesh.triangles.size(), 3u);
  EXPECT_EQ(room.mesh.vertices.size(), 5u);
  EXPECT_NEAR(room.surfaceArea(), 2.5 * std::sin(2 * M_PI / 5), 1e-5);  // to_string keeps 6 decimals
}

TEST(RoomObj, ADirectoryIsNotAnObjFile) {
  const diffray::test::TempDir dir("obj_directory");
  EXPECT_EQ(loadErrorOf(dir.path.string()), dir.path.string() + ": is a directory");
}
