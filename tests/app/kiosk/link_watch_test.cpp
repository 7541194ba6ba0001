// The IR tracker's link as the main loop sees it: each change once, and a loss that the
// reading thread reopened before the loop looked again still told, with its reason.
#include <gtest/gtest.h>

#include "app/kiosk/link_watch.hpp"

namespace mallet::app {
namespace {

IrLink link(bool up, std::uint64_t drops = 0, std::string last_drop = {}, std::string problem = {}) {
  IrLink l;
  l.present = true;
  l.up = up;
  l.identity = "camera vivid";
  l.problem = std::move(problem);
  l.drops = drops;
  l.last_drop = std::move(last_drop);
  return l;
}

TEST(LinkWatch, EachChangeIsToldOnceAndALossSaysWhy) {
  LinkWatch watch;
  EXPECT_TRUE(watch.look(link(false, 0, {}, "not opened yet")).empty());  // down from the start: nothing lost
  std::vector<LinkChange> c = watch.look(link(true));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_TRUE(c[0].connected);
  EXPECT_TRUE(watch.up());
  EXPECT_TRUE(watch.look(link(true)).empty());
  c = watch.look(link(false, 1, "/dev/video0: No such device", "/dev/video0: No such device"));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_FALSE(c[0].connected);
  EXPECT_EQ(c[0].why, "/dev/video0: No such device");
  EXPECT_FALSE(watch.up());
  // Back, after more failed attempts while it was seen down: one connection, no extra loss.
  c = watch.look(link(true, 3, "/dev/video0: No such device"));
  ASSERT_EQ(c.size(), 1u);
  EXPECT_TRUE(c[0].connected);
  EXPECT_TRUE(watch.look(link(true, 3, "/dev/video0: No such device")).empty());
}

TEST(LinkWatch, ALossReopenedBetweenTwoLooksIsStillToldThenTheConnection) {
  LinkWatch watch;
  watch.look(link(true));
  // The camera went away and was open again before the next look (a slow frame).
  const std::vector<LinkChange> c = watch.look(link(true, 2, "/dev/video0: No such device"));
  ASSERT_EQ(c.size(), 2u);
  EXPECT_FALSE(c[0].connected);
  EXPECT_EQ(c[0].why, "/dev/video0: No such device");
  EXPECT_TRUE(c[1].connected);
  EXPECT_TRUE(watch.up());
  EXPECT_TRUE(watch.look(link(true, 2, "/dev/video0: No such device")).empty());
}

}  // namespace
}  // namespace mallet::app
