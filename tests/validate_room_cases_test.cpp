// The room validation cases run end to end through the registry, as `diffray validate` runs them. Each
// case carries its own oracle and pass rule (src/validate/room_cases.cpp, decay_cases.cpp); here they must
// pass, and the figures that make the pass meaningful are checked too.
#include <gtest/gtest.h>

#include "diffray/validate/case.h"

namespace {

namespace dv = diffray::validate;

dv::CaseResult runCase(const std::string& name, std::uint64_t rays, const dv::Params& given = {}) {
  const dv::CaseInfo* info = dv::findCase(name);
  EXPECT_NE(info, nullptr) << name;
  dv::RunOptions ro;
  ro.rays = rays;
  ro.seed = 3;
  return info->run(dv::resolveParams(*info, given), ro);
}

TEST(StatValidateRoom, FreeFieldFluenceDelayAndHitFraction) {
  const auto r = runCase("free-field", 1'000'000);
  EXPECT_TRUE(r.passed) << r.detail;
  EXPECT_LE(r.extra.at("worst_sigmas"), 5.0);
  EXPECT_LT(r.max_std_error_rel_peak, 0.01);  // 5σ is a tight test: below 5 % of the fluence
}

TEST(ValidateRoom, ShoeboxImagesMatchTheLatticeExactly) {
  const auto r = runCase("shoebox-ism", 0, {{"order", {5}}});
  EXPECT_TRUE(r.passed) << r.detail;
  EXPECT_EQ(r.extra.at("images_reference"), 231.0);  // (2N+1)(2N²+2N+3)/3 at N = 5
  EXPECT_LT(r.extra.at("worst_energy_rel_error"), 1e-12);
  EXPECT_LT(r.extra.at("worst_delay_error_s"), 1e-12);
}

TEST(ValidateRoom, ShoeboxImagesHonourTheSourcePosition) {
  const auto r = runCase("shoebox-ism", 0, {{"source", {1, 1, 1}}, {"listener", {9, 6, 2.5}}, {"order", {3}}});
  EXPECT_TRUE(r.passed) << r.detail;
}

}  // namespace
