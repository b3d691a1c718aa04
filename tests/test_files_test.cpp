// The tests themselves: each writes only inside its own temporary folder (tests/temp_dir.h, named with the
// process id and removed with everything in it), never a fixed name in the shared temporary directory, so
// two runs at once cannot collide and nothing is left behind. Checked on the test sources' text.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

TEST(TestFiles, UseOnlyTheirOwnTemporaryFolders) {
  // Spelled in pieces so that this file does not match itself.
  const std::vector<std::string> forbidden = {std::string("/") + "tmp", std::string("testing::") + "TempDir()",
                                              std::string("temp_directory") + "_path()"};
  int files = 0;
  for (const auto& entry : fs::directory_iterator(fs::path(DIFFRAY_SOURCE_DIR) / "tests")) {
    const std::string name = entry.path().filename().string();
    const std::string ext = entry.path().extension().string();
    if (!(ext == ".cpp" || ext == ".h" || ext == ".sh") || name == "temp_dir.h") continue;
    std::ifstream in(entry.path());
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ++files;
    for (const std::string& f : forbidden)
      EXPECT_EQ(text.find(f), std::string::npos) << name << " uses " << f << " (use tests/temp_dir.h)";
  }
  EXPECT_GT(files, 50);
}

}  // namespace
