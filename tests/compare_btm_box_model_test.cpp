// compare's BTM exact model of a rigid box (compare/btm_model.h, btmBoxModelFor): which scenes get it, and
// that it is the box the scene holds. The box's corners and the ground are written here by hand and handed
// to the reference (reference/btm_box.h, itself checked against the right-angled wedge, reciprocity and
// continuity in reference_btm_box_test.cpp); the model must read the same box out of the scene's mesh and
// give p/p_free = u·R·e^{ikR}. Scenes it does not fit get no exact model, with the reason.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "diffray/compare/btm_model.h"
#include "diffray/compare/point_models.h"
#include "diffray/core/error.h"
#include "diffray/reference/btm_box.h"
#include "diffray/room/scene_file.h"

namespace {

namespace dc = diffray::compare;
namespace dr = diffray::room;
namespace ref = diffray::reference;
using diffray::core::Vec3;
constexpr double kPi = 3.14159265358979323846;
constexpr double kC = 343.0;

const std::string kBox =
    R"({"box": {"name": "cupboard", "min": [-0.3, -0.2, 0], "max": [0.3, 0.2, 0.6], "materials": {"all": "rigid"}}})";
const std::string kRigidGround =
    R"({"polygon": {"name": "ground", "vertices": [[-9, -9, 0], [9, -9, 0], [9, 9, 0], [-9, 9, 0]], "material": "rigid"}})";

// A scene with `geometry` (a JSON list's items), source S and listener L.
dr::Room scene(const std::string& geometry, const Vec3& listener = Vec3(0.1, 1.0, 0.4), double radius = 0.05,
               const Vec3& source = Vec3(0.05, -1.0, 0.3)) {
  const auto v = [](const Vec3& p) {
    return "[" + std::to_string(p.x()) + ", " + std::to_string(p.y()) + ", " + std::to_string(p.z()) + "]";
  };
  const std::string text = R"({"name": "box", "materials": {
      "rigid": {"absorption": 0.0, "scattering": 0.0}, "soak": {"absorption": 0.3, "scattering": 0.0}},
    "geometry": [)" + geometry + R"(],
    "sources": [{"name": "S", "position": )" + v(source) + R"(}],
    "listeners": [{"name": "L", "position": )" + v(listener) + R"(, "radius_m": )" + std::to_string(radius) + R"(}],
    "air": {"speed_of_sound_m_s": 343}})";
  return dr::parseRoom(text, "box.json", ".");
}

// A face of the box [−0.3, 0.3] × [−0.2, 0.2] × [0, 0.6] as a polygon, by hand.
std::string face(const std::string& name, const std::vector<Vec3>& corners, const std::string& material = "rigid") {
  std::string out = R"({"polygon": {"name": ")" + name + R"(", "material": ")" + material + R"(", "vertices": [)";
  for (std::size_t i = 0; i < corners.size(); ++i)
    out += (i ? ", [" : "[") + std::to_string(corners[i].x()) + ", " + std::to_string(corners[i].y()) + ", " +
           std::to_string(corners[i].z()) + "]";
  return out + "]}}";
}

// The five faces above the ground, polygons; `top_material` for the top.
std::string fiveFaces(const std::string& top_material = "rigid") {
  const double x0 = -0.3, x1 = 0.3, y0 = -0.2, y1 = 0.2, z1 = 0.6;
  return face("x-", {Vec3(x0, y0, 0), Vec3(x0, y1, 0), Vec3(x0, y1, z1), Vec3(x0, y0, z1)}) + "," +
         face("x+", {Vec3(x1, y0, 0), Vec3(x1, y1, 0), Vec3(x1, y1, z1), Vec3(x1, y0, z1)}) + "," +
         face("y-", {Vec3(x0, y0, 0), Vec3(x1, y0, 0), Vec3(x1, y0, z1), Vec3(x0, y0, z1)}) + "," +
         face("y+", {Vec3(x0, y1, 0), Vec3(x1, y1, 0), Vec3(x1, y1, z1), Vec3(x0, y1, z1)}) + "," +
         face("top", {Vec3(x0, y0, z1), Vec3(x1, y0, z1), Vec3(x1, y1, z1), Vec3(x0, y1, z1)}, top_material);
}

void expectTheBox(const dr::Room& room, bool ground) {
  std::string why, assumption;
  const auto model = dc::exactModelFor(room, kC, why, assumption);
  ASSERT_NE(model, nullptr) << why;
  EXPECT_EQ(model->name(), "exact");
  EXPECT_FALSE(model->addsEnergies());
  EXPECT_NE(assumption.find("BTM"), std::string::npos) << assumption;
  EXPECT_NE(assumption.find("0.6 x 0.4 x 0.6 m box"), std::string::npos) << assumption;
  EXPECT_EQ(assumption.find("rigid ground") != std::string::npos, ground) << assumption;
  const ref::BtmBox box{Vec3(-0.3, -0.2, 0.0), Vec3(0.3, 0.2, 0.6)};
  const Vec3 s = room.sources[0].position_m;
  const Vec3 l(0.1, 1.0, 0.4);  // behind the box, in its shadow
  {
    const std::vector<double> f{200.0, 900.0};
    const std::vector<std::complex<double>> p = model->relativePressure(s, l, f);
    for (std::size_t i = 0; i < f.size(); ++i) {
      const double k = 2.0 * kPi * f[i] / kC, r = (l - s).norm();
      const ref::BtmBoxField u = ground ? ref::btmBoxOnGroundField(k, box, 0.0, s, l) : ref::btmBoxField(k, box, s, l);
      const std::complex<double> expected = u.total() * r * std::polar(1.0, k * r);
      // The spectrum against one frequency at a time: ~1e-12 of the free field (btm_box.h).
      EXPECT_LT(std::abs(p[i] - expected), 1e-9) << f[i] << " Hz at " << l.transpose();
    }
  }
}

}  // namespace

TEST(CompareBtmBoxModel, BoxOnARigidGroundIsTheBoxOnTheGround) { expectTheBox(scene(kRigidGround + "," + kBox), true); }

TEST(CompareBtmBoxModel, BoxAloneIsTheFreeBox) { expectTheBox(scene(kBox), false); }

TEST(CompareBtmBoxModel, FiveFacesOnAGroundAreTheSameBox) { expectTheBox(scene(kRigidGround + "," + fiveFaces()), true); }

TEST(CompareBtmBoxModel, OtherScenesGetNoExactModel) {
  // An absorbing face or ground, the bottom missing in free field, a box floating above the ground, a wall
  // beside it, a tilted face: no exact model, and the reason says why.
  const std::string wall = face("wall", {Vec3(2, -1, 0), Vec3(2, 1, 0), Vec3(2, 1, 1), Vec3(2, -1, 1)});
  const std::string floating =
      R"({"box": {"name": "shelf", "min": [-0.3, -0.2, 0.5], "max": [0.3, 0.2, 0.9], "materials": {"all": "rigid"}}})";
  const std::string tilted_top = face("top", {Vec3(-0.3, -0.2, 0.6), Vec3(0.3, -0.2, 0.6), Vec3(0.3, 0.2, 0.7), Vec3(-0.3, 0.2, 0.7)});
  const std::string soaking_ground =
      R"({"polygon": {"name": "ground", "vertices": [[-9, -9, 0], [9, -9, 0], [9, 9, 0], [-9, 9, 0]], "material": "soak"}})";
  const struct {
    std::string geometry, reason;
  } cases[] = {
      {kRigidGround + "," + fiveFaces("soak"), "absorbs"},
      {soaking_ground + "," + kBox, "absorbs"},
      {fiveFaces(), "bottom face is 0 m² covered of 0.24 m²"},
      {kRigidGround + "," + floating, "standing on the lowest plane"},
      {kRigidGround + "," + kBox + "," + wall, "is not on a face of the box"},
      {kRigidGround + "," + fiveFaces().substr(0, fiveFaces().rfind(",{")) + "," + tilted_top, "is not on a face of the box"},
  };
  for (const auto& c : cases) {
    std::string why, assumption;
    EXPECT_EQ(dc::exactModelFor(scene(c.geometry), kC, why, assumption), nullptr) << c.geometry;
    EXPECT_NE(why.find(c.reason), std::string::npos) << why;
  }
}

TEST(CompareBtmBoxModel, PointsInsideOrOnTheBoxAreRefused) {
  // A listener whose sphere meets the box, and a source inside it: one line naming them.
  std::string why, assumption;
  try {
    dc::exactModelFor(scene(kRigidGround + "," + kBox, Vec3(0.0, 0.24, 0.3), 0.05), kC, why, assumption);
    ADD_FAILURE() << "a listener touching the box was taken";
  } catch (const diffray::core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("listener L: its sphere (radius 0.05 m) meets the box"), std::string::npos) << e.what();
  }
  try {
    dc::exactModelFor(scene(kRigidGround + "," + kBox, Vec3(0.1, 1.0, 0.4), 0.05, Vec3(0.0, 0.0, 0.3)), kC, why, assumption);
    ADD_FAILURE() << "a source inside the box was taken";
  } catch (const diffray::core::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("source S lies inside or on the box"), std::string::npos) << e.what();
  }
}

TEST(CompareBtmBoxModel, NoValueAboveTheSizeLimit) {
  // On the ground the box joined with its mirror is 0.6 × 0.4 × 1.2 m: 8.8 m of edges, so the reference
  // stops at 360 wavelengths, 360·343/8.8 = 14032 Hz. Above it: NaN.
  const dr::Room room = scene(kRigidGround + "," + kBox);
  std::string why, assumption;
  const auto model = dc::btmBoxModelFor(room, kC, why, assumption);
  ASSERT_NE(model, nullptr) << why;
  EXPECT_NE(assumption.find("up to 14032 Hz"), std::string::npos) << assumption;
  const Vec3 s = room.sources[0].position_m, l = room.listeners[0].position_m;
  const std::vector<std::complex<double>> p = model->relativePressure(s, l, {200.0, 14100.0});
  EXPECT_TRUE(std::isfinite(std::abs(p[0])));
  EXPECT_TRUE(std::isnan(p[1].real()) && std::isnan(p[1].imag()));
}
