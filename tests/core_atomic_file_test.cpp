// Output files: written whole or not at all (writeFileAtomically), and a command's set replaced together
// (OutputFiles): a failure part-way through a rerun must leave the previous run's files as they were.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "diffray/core/atomic_file.h"
#include "diffray/core/error.h"
#include "temp_dir.h"

namespace dc = diffray::core;
namespace fs = std::filesystem;

namespace {

std::string contents(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void writeText(const std::string& path, const std::string& text) {
  dc::writeFileAtomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace

TEST(CoreAtomicFile, WritesWholeFileAndLeavesNoTemporary) {
  const diffray::test::TempDir dir("atomic_whole");
  const fs::path& d = dir.path;
  writeText((d / "a.txt").string(), "hello");
  EXPECT_EQ(contents(d / "a.txt"), "hello");
  EXPECT_EQ(dir.entries(), 1);
}

TEST(CoreAtomicFile, FailedWriteLeavesTargetUntouched) {
  const diffray::test::TempDir dir("atomic_failed");
  const fs::path& d = dir.path;
  writeText((d / "a.txt").string(), "old");
  EXPECT_THROW(dc::writeFileAtomically((d / "a.txt").string(),
                                       [](std::ostream& out) {
                                         out << "new, half";
                                         throw std::runtime_error("writer failed");
                                       }),
               std::runtime_error);
  EXPECT_EQ(contents(d / "a.txt"), "old");
  EXPECT_EQ(dir.entries(), 1);
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
  const diffray::test::TempDir dir("atomic_commit");
  const fs::path& d = dir.path;
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
  EXPECT_EQ(dir.entries(), 2);
}

// writeEach: several files written in parallel, each from its index, staged and committed as write() does;
// one writer failing leaves the previous run's files.
TEST(CoreOutputFiles, WriteEachWritesEveryFileFromItsIndex) {
  const diffray::test::TempDir dir("atomic_each");
  const fs::path& d = dir.path;
  std::vector<std::string> paths;
  for (int i = 0; i < 6; ++i) paths.push_back((d / ("f" + std::to_string(i) + ".txt")).string());
  writeText(paths[3], "old 3");
  {
    dc::OutputFiles files;
    files.writeEach(paths, [](std::size_t i, const std::string& f) { writeText(f, "new " + std::to_string(i)); });
    EXPECT_EQ(contents(paths[3]), "old 3");
    files.commit();
  }
  for (int i = 0; i < 6; ++i) EXPECT_EQ(contents(paths[static_cast<std::size_t>(i)]), "new " + std::to_string(i));
  try {
    dc::OutputFiles files;
    files.writeEach(paths, [&](std::size_t i, const std::string& f) {
      if (i == 4) throw dc::InputError(f, "cannot write");
      writeText(f, "run 3");
    });
    FAIL() << "the fifth writer should have thrown";
  } catch (const dc::InputError& e) {
    EXPECT_EQ(e.where(), paths[4]);
  }
  for (int i = 0; i < 6; ++i) EXPECT_EQ(contents(paths[static_cast<std::size_t>(i)]), "new " + std::to_string(i));
  EXPECT_EQ(dir.entries(), 6);
}

TEST(CoreOutputFiles, LaterFailureKeepsThePreviousRunsFiles) {
  const diffray::test::TempDir dir("atomic_rerun");
  const fs::path& d = dir.path;
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
  EXPECT_EQ(dir.entries(), 3);  // no staged file left
}

TEST(CoreOutputFiles, FirstRunFailureLeavesNothing) {
  const diffray::test::TempDir dir("atomic_first");
  const fs::path& d = dir.path;
  try {
    dc::OutputFiles files;
    files.write((d / "a.wav").string(), [](const std::string& f) { writeText(f, "a"); });
    throw dc::InputError("plot", "gnuplot failed");
  } catch (const dc::InputError&) {
  }
  EXPECT_EQ(dir.entries(), 0);
}

// A writer's error names the file the user asked for, not the staging file it was writing.
TEST(CoreOutputFiles, WriterErrorsNameTheTarget) {
  const diffray::test::TempDir dir("atomic_message");
  const fs::path& d = dir.path;
  const std::string target = (d / "a.wav").string();
  try {
    dc::OutputFiles files;
    files.write(target, [](const std::string& f) { throw dc::InputError(f, "write failed (" + f + ")"); });
    FAIL() << "the write should have thrown";
  } catch (const dc::InputError& e) {
    EXPECT_EQ(e.where(), target);
    EXPECT_EQ(std::string(e.what()), target + ": write failed (" + target + ")");
  }
  EXPECT_EQ(dir.entries(), 0);
}

// A rename that fails (the target is a folder) is reported naming it; the files not renamed are removed.
TEST(CoreOutputFiles, FailedCommitNamesTheTargetAndCleansUp) {
  const diffray::test::TempDir dir("atomic_commitfail");
  const fs::path& d = dir.path;
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
  EXPECT_EQ(dir.entries(), 2);                // a.wav and the folder
}
