// Progress in a log (stderr not a terminal, as under ctest): one line per tenth of a count, with
// its rate once it has one; nothing with --quiet or for the Python module (its callback hears it).
#include "roving/measurement/progress.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace roving {
namespace {

std::size_t lines(const std::string& text) { return std::count(text.begin(), text.end(), '\n'); }

TEST(ProgressLog, OneLinePerTenthOfEachCount) {
  ::testing::internal::CaptureStderr();
  {
    Progress progress(false, true, 0);  // log from the start, not after 5 s
    progress.stage("measuring");
    for (std::size_t done = 0; done <= 1000; done += 7) progress.update("samples", done, 1000);
    progress.update("samples", 1000, 1000);
    progress.update("cameras", 3, 4);  // a new count starts its own tenths
  }
  const std::string log = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(lines(log), 11u) << log;  // 10%, 20%, ... 100% of samples, then 75% of cameras
  EXPECT_NE(log.find("roving: measuring: samples 105/1000 (10%)"), std::string::npos) << log;
  EXPECT_NE(log.find("roving: measuring: samples 1000/1000 (100%)\n"), std::string::npos) << log;
  EXPECT_NE(log.find("roving: measuring: cameras 3/4 (75%)"), std::string::npos) << log;
}

TEST(ProgressLog, SilentWhenQuietForShortCountsAndForPython) {
  for (const auto& [quiet, log_lines, after] : {std::tuple{true, true, 0.0}, {false, true, 60.0}, {false, false, 0.0}}) {
    ::testing::internal::CaptureStderr();
    {
      Progress progress(quiet, log_lines, after);
      progress.stage("measuring");
      for (std::size_t done = 0; done <= 100; ++done) progress.update("samples", done, 100);
    }
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
  }
}

}  // namespace
}  // namespace roving
