// Output files: written whole or not at all (writeFileAtomically), and a command's set replaced together
// (OutputFiles): a failure part-way through a rerun must leave the previous run's files as they were.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "diffray/core/atomic_file.h"
#include "diffray/core/error.h"

namespace dc = diffray::core;
namespace fs = std::filesystem;

namespace {

// A fresh, empty folder for one test.
fs::path freshDir(const std::string& name) {
  const fs::path d = fs::temp_directory_path() / ("diffray_atomic_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string contents(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void writeText(const std::string& path, const std::string& text) {
  dc::writeFileAtomically(path, [&](std::ostream& out) { out << text; });
}

std::size_t filesIn(const fs::path& d) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(d), fs::directory_iterator()));
}

}  // namespace

TEST(CoreAtomicFile, WritesWholeFileAndLeavesNoTemporary) {
  const fs::path d = freshDir("whole");
  writeText((d / "a.txt").string(), "hello");
  EXPECT_EQ(contents(d / "a.txt"), "hello");
  EXPECT_EQ(filesIn(d), 1u);
  fs::remove_all(d);
}

TEST(CoreAtomicFile, FailedWriteLeavesTargetUntouched) {
  const fs::path d = freshDir("failed");
  writeText((d / "a.txt").string(), "old");
  EXPECT_THROW(dc::writeFileAtomically((d / "a.txt").string(),
                                       [](std::ostream& out) {
                                         out << "new, half";
                                         throw std::runtime_error("writer failed");
                                       }),
               std::runtime_error);
  EXPECT_EQ(contents(d / "a.txt"), "old");
  EXPECT_EQ(filesIn(d), 1u);
  fs::remove_all(d);
}

TEST(CoreOutputFiles, StagingNameKeepsFolderAndExtension) {
  const std::string s = dc::OutputFiles::stagingName("out/impulse.wav", 2);
  const fs::path p(s);
  EXPECT_EQ(p.parent_path(), fs::path("out"));
  EXPECT_EQ(p.extension(), ".wav");
  EXPECT_NE(p.filename(), fs::path("impulse.wav"));
  EXPECT_NE(s, dc::OutputFiles::stagingName("out/impulse.wav", 3));  // two outputs never share one
}

TEST(CoreOutputFiles, CommitReplacesEveryFile) {
  const fs::path d = freshDir("commit");
  const std::string a = (d / "a.wav").string(), b = (d / "a.json").string();
  writeText(a, "old a");
  writeText(b, "old b");
  {
    dc::OutputFiles files;
    files.write(a, [](const std::string& f) { writeText(f, "new a"); });
    files.write(b, [](const std::string& f) { writeText(f, "new b"); });
    EXPECT_EQ(contents(a), "old a");  // nothing replaced before the commit
    files.commit();
  }
  EXPECT_EQ(contents(a), "new a");
  EXPECT_EQ(contents(b), "new b");
  EXPECT_EQ(filesIn(d), 2u);
  fs::remove_all(d);
}

TEST(CoreOutputFiles, LaterFailureKeepsThePreviousRunsFiles) {
  const fs::path d = freshDir("rerun");
  const std::string a = (d / "a.wav").string(), b = (d / "a.csv").string(), c = (d / "a.json").string();
  writeText(a, "run 1 a");
  writeText(b, "run 1 b");
  writeText(c, "run 1 c");
  try {
    dc::OutputFiles files;
    files.write(a, [](const std::string& f) { writeText(f, "run 2 a"); });
    files.write(b, [](const std::string& f) { writeText(f, "run 2 b"); });
    files.write(c, [](const std::string&) { throw dc::InputError("a.json", "cannot write"); });
    files.commit();
    FAIL() << "the third write should have thrown";
  } catch (const dc::InputError&) {
  }
  EXPECT_EQ(contents(a), "run 1 a");
  EXPECT_EQ(contents(b), "run 1 b");
  EXPECT_EQ(contents(c), "run 1 c");
  EXPECT_EQ(filesIn(d), 3u);  // no staged file left
  fs::remove_all(d);
}

TEST(CoreOutputFiles, FirstRunFailureLeavesNothing) {
  const fs::path d = freshDir("first");
  try {
    dc::OutputFiles files;
    files.write((d / "a.wav").string(), [](const std::string& f) { writeText(f, "a"); });
    throw dc::InputError("plot", "gnuplot failed");
  } catch (const dc::InputError&) {
  }
  EXPECT_EQ(filesIn(d), 0u);
  fs::remove_all(d);
}

// A writer's error names the file the user asked for, not the staging file it was writing.
TEST(CoreOutputFiles, WriterErrorsNameTheTarget) {
  const fs::path d = freshDir("message");
  const std::string target = (d / "a.wav").string();
  try {
    dc::OutputFiles files;
    files.write(target, [](const std::string& f) { throw dc::InputError(f, "write failed (" + f + ")"); });
    FAIL() << "the write should have thrown";
  } catch (const dc::InputError& e) {
    EXPECT_EQ(e.where(), target);
    EXPECT_EQ(std::string(e.what()), target + ": write failed (" + target + ")");
  }
  EXPECT_EQ(filesIn(d), 0u);
  fs::remove_all(d);
}

// A rename that fails (the target is a folder) is reported naming it; the files not renamed are removed.
TEST(CoreOutputFiles, FailedCommitNamesTheTargetAndCleansUp) {
  const fs::path d = freshDir("commitfail");
  fs::create_directories(d / "b.csv" / "inside");  // a non-empty folder: no file can be renamed over it
  const std::string a = (d / "a.wav").string(), b = (d / "b.csv").string(), c = (d / "c.json").string();
  try {
    dc::OutputFiles files;
    files.write(a, [](const std::string& f) { writeText(f, "a"); });
    files.write(b, [](const std::string& f) { writeText(f, "b"); });
    files.write(c, [](const std::string& f) { writeText(f, "c"); });
    files.commit();
    FAIL() << "the commit should have thrown";
  } catch (const dc::InputError& e) {
    EXPECT_EQ(e.where(), b);
  }
  EXPECT_EQ(contents(a), "a");              // renamed before the failure: stays
  EXPECT_TRUE(fs::is_directory(b));         // untouched
  EXPECT_FALSE(fs::exists(c));              // not renamed, and its staged file removed
  EXPECT_EQ(filesIn(d), 2u);                // a.wav and the folder
  fs::remove_all(d);
}
