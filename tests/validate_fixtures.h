#pragma once
// Shared by the validation-case tests: runs a case through the registry, as `diffray validate` does.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "diffray/validate/case.h"

namespace diffray::testing {

inline validate::CaseResult runCase(const std::string& name, std::uint64_t rays, const validate::Params& given = {},
                                    std::uint64_t seed = 12345) {
  const validate::CaseInfo* info = validate::findCase(name);
  EXPECT_NE(info, nullptr) << name;
  validate::RunOptions ro;
  ro.rays = rays;
  ro.seed = seed;
  return info->run(validate::resolveParams(*info, given), ro);
}

}  // namespace diffray::testing
