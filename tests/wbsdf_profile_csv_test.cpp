// The profile CSV reader's numbers: decimal only, as every option and every other reader reads them (a hex
// float such as 0x1p1 is refused, not read as 2), and the "too long" refusal of a profile whose sample count
// exceeds every integer type stating that count as the number it is.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "diffray/core/error.h"
#include "diffray/wbsdf/profile_csv.h"
#include "temp_dir.h"

namespace dw = diffray::wbsdf;

namespace {

using diffray::test::TempDir;

/// The error readProfileCsv gives for `content`, or "(no error)".
std::string csvError(const std::string& content) {
  const TempDir dir("profile_csv");
  std::ofstream(dir.file("p.csv")) << content;
  try {
    dw::readProfileCsv(dir.file("p.csv"));
  } catch (const diffray::core::InputError& e) {
    const std::string what = e.what();
    return what.substr(what.find("p.csv"));
  }
  return "(no error)";
}

TEST(ProfileCsvNumbers, DecimalOnly) {
  EXPECT_EQ(csvError("x,a,phi\n0,1,0\n1e-3,1,0.5\n"), "(no error)");
  EXPECT_EQ(csvError("0,1,0\n.5,1,-2.5E-1\n"), "(no error)");
  EXPECT_EQ(csvError("0,1,0\n0x1p1,1,0\n"), "p.csv:2: column 'x' is not a number: '0x1p1'");
  EXPECT_EQ(csvError("0,1,0\n1,0x1p-1,0\n"), "p.csv:2: column 'amplitude' is not a number: '0x1p-1'");
  // A hex first line is data, not a header to skip.
  EXPECT_EQ(csvError("0x0p0,1,0\n1,1,0\n2,1,0\n"), "p.csv:1: column 'x' is not a number: '0x0p0'");
  // nan and inf are words, not numbers (as for every option); 1e999 is a number, out of range.
  EXPECT_EQ(csvError("0,1,0\n1,nan,0\n"), "p.csv:2: column 'amplitude' is not a number: 'nan'");
  EXPECT_EQ(csvError("nan,1,0\n1,1,0\n"), "p.csv:1: column 'x' is not a number: 'nan'");
  EXPECT_EQ(csvError("0,1,0\n1,1,-inf\n"), "p.csv:2: column 'phase' is not a number: '-inf'");
  EXPECT_EQ(csvError("0,1,0\n1e999,1,0\n"), "p.csv:2: column 'x' is not finite: '1e999'");
}

TEST(ProfileCsvNumbers, TooLongStatesTheSampleCount) {
  // 3e83 m at dx = λ/32: about 1.9e89 samples, beyond every integer type.
  const dw::ProfilePoints points{{0.0, 3e83}, {1.0, 1.0}, {0.0, 1.0}};
  try {
    dw::profileTable(points, 500e-9);
    FAIL() << "no error";
  } catch (const diffray::core::InputError& e) {
    const std::string what = e.what();
    const std::size_t open = what.find('(');
    ASSERT_NE(open, std::string::npos) << what;
    const double stated = std::strtod(what.c_str() + open + 1, nullptr);
    EXPECT_NEAR(stated / (3e83 / (500e-9 / 32.0)), 1.0, 1e-3) << what;
  }
}

}  // namespace
