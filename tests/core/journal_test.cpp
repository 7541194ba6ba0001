// The journal's lines: the syslog priority in front, the text formatted by {fmt}, one line
// each.
#include <gtest/gtest.h>

#include "core/journal.hpp"

namespace mallet {
namespace {

TEST(Journal, EachLineCarriesItsPriorityAndEndsOnce) {
  testing::internal::CaptureStderr();
  journal::error("visitor study: {}", "no file");
  journal::warning("reload refused: {} at line {}", "mallet.toml", 3);
  journal::notice("operator: volume {:.0f} %", 79.6);
  journal::info("frames paced at {:.1f} a second", 59.94);
  EXPECT_EQ(testing::internal::GetCapturedStderr(),
            "<3>visitor study: no file\n"
            "<4>reload refused: mallet.toml at line 3\n"
            "<5>operator: volume 80 %\n"
            "<6>frames paced at 59.9 a second\n");
}

}  // namespace
}  // namespace mallet
