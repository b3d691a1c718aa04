#pragma once
// Shared by the validation-case tests: runs a case through the registry, as `diffray validate` does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
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

// Chi-square of the image case's rows: each column's rendered radiance against the oracle, in units of its
// standard error. Unbiased estimators give χ²/dof ≈ 1 (sd √(2/n)) and no column beyond ~4.5 σ (480 columns).
inline void expectRowsMatch(const validate::CaseResult& r) {
  double chi2 = 0.0, max_z = 0.0;
  for (const auto& row : r.rows) {
    ASSERT_GT(row.std_error, 0.0);
    const double z = (row.traced - row.reference) / row.std_error;
    chi2 += z * z;
    max_z = std::max(max_z, std::abs(z));
  }
  const double n = static_cast<double>(r.rows.size());
  std::printf("%s: chi2/dof %.3f, max |z| %.2f, max error %.4f of peak (largest std error %.4f of peak)\n",
              r.name.c_str(), chi2 / n, max_z, r.max_abs_error_rel_peak, r.max_std_error_rel_peak);
  EXPECT_LT(max_z, 4.5);
  EXPECT_NEAR(chi2 / n, 1.0, 5.0 * std::sqrt(2.0 / n));
  // The largest error is within 4.5 of the largest standard errors: noise, not bias.
  EXPECT_LT(r.max_abs_error_rel_peak, 4.5 * r.max_std_error_rel_peak);
}

}  // namespace diffray::testing
