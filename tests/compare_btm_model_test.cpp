// compare's BTM exact model (compare/btm_model.h): which scenes get it, and that it is the plate the scene
// holds. The plate's corners and the ground are written here by hand and handed to the reference
// (reference/btm_plate.h, itself checked against Macdonald's half-plane in reference_btm_test.cpp); the
// model must read the same plate out of the scene's mesh and give p/p_free = u·R·e^{ikR}. Scenes outside
// its reach fall back to the half-plane reference, and frequencies above its size limit get no value.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <string>
#include <vector>

#include "diffray/compare/btm_model.h"
#include "diffray/compare/point_models.h"
#include "diffray/reference/btm_plate.h"
#include "diffray/room/scene_file.h"

namespace {

namespace dc = diffray::compare;
namespace dr = diffray::room;
namespace ref = diffray::reference;
using diffray::core::Vec3;
constexpr double kPi = 3.14159265358979323846;
constexpr double kC = 343.0;

// A 1 m wide, 0.5 m high barrier in the plane y = 0 standing on z = 0; `ground` is the geometry list (may
// be empty), `faces` and the panel's absorption as given.
dr::Room plateScene(const std::string& ground, const std::string& panel_absorption = "0.0",
                    const std::string& faces = "rigid") {
  const std::string text = R"({"name": "plate", "materials": {
      "rigid": {"absorption": 0.0, "scattering": 0.0}, "soak": {"absorption": 1.0, "scattering": 0.0},
      "panel": {"absorption": )" + panel_absorption + R"(, "scattering": 0.0}},
    )" + (ground.empty() ? "" : "\"geometry\": [" + ground + "],") + R"(
    "occluders": [{"type": "barrier", "name": "wall", "base": [[-0.5, 0, 0], [0.5, 0, 0]], "height_m": 0.5,
                   "material": "panel", "faces": ")" + faces + R"("}],
    "sources": [{"name": "S", "position": [0.1, -1.0, 0.2]}],
    "listeners": [{"name": "L", "position": [-0.2, 1.0, 0.3], "radius_m": 0.05}],
    "air": {"speed_of_sound_m_s": 343}})";
  return dr::parseRoom(text, "plate.json", ".");
}

const std::string kRigidGround =
    R"({"polygon": {"name": "ground", "vertices": [[-9, -9, 0], [9, -9, 0], [9, 9, 0], [-9, 9, 0]], "material": "rigid"}})";
const std::string kSoakingGround =
    R"({"polygon": {"name": "ground", "vertices": [[-9, -9, 0], [9, -9, 0], [9, 9, 0], [-9, 9, 0]], "material": "soak"}})";

// The plate of plateScene, by hand.
ref::BtmPlate handPlate() {
  return ref::BtmPlate{{Vec3(-0.5, 0, 0), Vec3(0.5, 0, 0), Vec3(0.5, 0, 0.5), Vec3(-0.5, 0, 0.5)}};
}

void expectTheReference(const dr::Room& room, double ground_z) {
  std::string why, assumption;
  const auto model = dc::exactModelFor(room, kC, why, assumption);
  ASSERT_NE(model, nullptr) << why;
  EXPECT_EQ(model->name(), "exact");
  EXPECT_FALSE(model->addsEnergies());
  EXPECT_NE(assumption.find("BTM"), std::string::npos) << assumption;
  EXPECT_EQ(assumption.find("rigid ground") != std::string::npos, !std::isnan(ground_z)) << assumption;
  const Vec3 s = room.sources[0].position_m;
  for (const Vec3& l : {Vec3(-0.2, 1.0, 0.3), Vec3(0.9, 0.6, 0.7)}) {  // behind, and beside the screen
    const std::vector<double> f{250.0, 900.0};
    const std::vector<std::complex<double>> p = model->relativePressure(s, l, f);
    for (std::size_t i = 0; i < f.size(); ++i) {
      const double k = 2.0 * kPi * f[i] / kC, r = (l - s).norm();
      const ref::BtmPlateField u = std::isnan(ground_z) ? ref::btmPlateField(k, handPlate(), s, l)
                                                         : ref::btmPlateOnGroundField(k, handPlate(), ground_z, s, l);
      const std::complex<double> expected = u.total() * r * std::polar(1.0, k * r);
      // The spectrum against one frequency at a time: ~1e-13 of the free field (btm_spectrum.h).
      EXPECT_LT(std::abs(p[i] - expected), 1e-9) << f[i] << " Hz at " << l.transpose();
    }
  }
}

TEST(CompareBtmModel, BarrierOnARigidGroundIsThePlateOnTheGround) { expectTheReference(plateScene(kRigidGround), 0.0); }

TEST(CompareBtmModel, BarrierWithoutGeometryIsTheFreePlate) { expectTheReference(plateScene(""), std::nan("")); }

TEST(CompareBtmModel, OtherScenesFallBackToTheHalfPlane) {
  // An absorbing ground (the half-plane on absorbing ground, as rooms/barrier.json), an absorbing panel,
  // soft faces, and a second surface away from the foot: no BTM reference, the half-plane's instead.
  const std::string wall =
      R"({"polygon": {"name": "wall", "vertices": [[3, -1, 0], [3, 1, 0], [3, 1, 2], [3, -1, 2]], "material": "rigid"}})";
  for (const dr::Room& room : {plateScene(kSoakingGround), plateScene(kRigidGround, "0.2"),
                               plateScene(kRigidGround, "0.0", "soft"), plateScene(kRigidGround + "," + wall)}) {
    std::string why, assumption;
    const auto model = dc::exactModelFor(room, kC, why, assumption);
    ASSERT_NE(model, nullptr) << why;
    EXPECT_NE(assumption.find("Macdonald"), std::string::npos) << assumption;
    std::string btm_why;
    EXPECT_EQ(dc::btmModelFor(room, kC, btm_why, assumption), nullptr);
    EXPECT_FALSE(btm_why.empty());
  }
}

TEST(CompareBtmModel, NoValueAboveTheSizeLimit) {
  // On the ground the plate joined with its mirror is 1 × 1 m: perimeter 4 m, so the reference stops at
  // 300 wavelengths, 300·343/4 = 25725 Hz. Above it: NaN, and a band there has no level.
  const dr::Room room = plateScene(kRigidGround);
  std::string why, assumption;
  const auto model = dc::btmModelFor(room, kC, why, assumption);
  ASSERT_NE(model, nullptr) << why;
  EXPECT_NE(assumption.find("up to 25725 Hz"), std::string::npos) << assumption;
  const Vec3 s = room.sources[0].position_m, l = room.listeners[0].position_m;
  const std::vector<std::complex<double>> p = model->relativePressure(s, l, {200.0, 25800.0});
  EXPECT_TRUE(std::isfinite(std::abs(p[0])));
  EXPECT_TRUE(std::isnan(p[1].real()) && std::isnan(p[1].imag()));
  EXPECT_TRUE(std::isnan(dc::bandRelativeEnergy(*model, s, l, 0.05, 26000.0, 27000.0, 4)));
}

}  // namespace
