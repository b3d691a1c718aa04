// core::TempRegistration: a run killed by SIGINT, SIGTERM or SIGHUP deletes the temporaries registered at
// that moment and still dies by the signal (its exit status unchanged for the shell). Oracle: the files on
// disk after a death test's child (forked at the check, "fast" style: no threads run yet in a test
// process) raised the signal, and the child's termination signal.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>

#include "temp_dir.h"
#include "diffray/core/temp_files.h"

namespace {

using diffray::core::TempRegistration;

void touch(const std::string& path) { std::ofstream(path) << "partial"; }

TEST(CoreTempFiles, AnInterruptDeletesRegisteredTemporariesAndStillKills) {
  for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
    SCOPED_TRACE(::testing::Message() << "signal " << sig);
    const diffray::test::TempDir dir("tempfiles");
    const std::string live = dir.file("out.wav.tmp.1"), released = dir.file("done.tmp"), other = dir.file("keep.txt");
    EXPECT_EXIT(
        {
          touch(live);
          touch(released);
          touch(other);
          const TempRegistration registered(live);
          { const TempRegistration done(released); }  // renamed or removed already: no longer registered
          std::raise(sig);
        },
        ::testing::KilledBySignal(sig), "");
    EXPECT_FALSE(std::filesystem::exists(live));
    EXPECT_TRUE(std::filesystem::exists(released));
    EXPECT_TRUE(std::filesystem::exists(other));
  }
}

TEST(CoreTempFiles, RegistrationsEndWithTheirScopeAndMove) {
  const diffray::test::TempDir dir("tempfiles_move");
  const std::string a = dir.file("a.tmp"), b = dir.file("b.tmp");
  EXPECT_EXIT(
      {
        touch(a);
        touch(b);
        TempRegistration first(a);
        const TempRegistration moved(std::move(first));  // still registered, once
        { const TempRegistration scoped(b); }
        std::raise(SIGTERM);
      },
      ::testing::KilledBySignal(SIGTERM), "");
  EXPECT_FALSE(std::filesystem::exists(a));
  EXPECT_TRUE(std::filesystem::exists(b));
}

}  // namespace
