// The visitor micro-study's offer times and what identifies a visitor: a random id and the
// date, nothing finer.
#include <gtest/gtest.h>

#include "core/study/study_protocol.hpp"
#include "core/study/visitor_offer.hpp"

namespace mallet::study {
namespace {

constexpr Nanos kS = kNanosPerSecond;

TEST(VisitorOffer, OfferedEveryPeriodForItsDurationAndMovedOnBySessions) {
  VisitorOffer offer(300 * kS, 30 * kS, 1000 * kS);  // the kiosk started at 1000 s
  EXPECT_FALSE(offer.offered(1000 * kS));
  EXPECT_FALSE(offer.offered(1299 * kS));
  EXPECT_TRUE(offer.offered(1300 * kS));
  EXPECT_TRUE(offer.offered(1329 * kS));
  EXPECT_FALSE(offer.offered(1330 * kS)) << "an offer nobody took goes";
  EXPECT_FALSE(offer.offered(1599 * kS));
  EXPECT_TRUE(offer.offered(1600 * kS));
  // Days later (the kiosk runs for weeks): still on its grid, without drift.
  const Nanos week = 7 * 86400 * kS;
  EXPECT_TRUE(offer.offered(1000 * kS + week + 300 * kS * 2));  // 7 days is a whole number of 300 s
  EXPECT_FALSE(offer.offered(1000 * kS + week + 300 * kS * 2 + 30 * kS));
  // A session that ended: the next offer is a whole period later, not at once.
  offer.session_ended(1000 * kS + week + 700 * kS);
  EXPECT_EQ(offer.next_offer(), 1000 * kS + week + 1000 * kS);
  EXPECT_FALSE(offer.offered(1000 * kS + week + 999 * kS));
  EXPECT_TRUE(offer.offered(1000 * kS + week + 1000 * kS));
}

TEST(VisitorOffer, AVisitorIsARandomIdAndADate) {
  EXPECT_EQ(visitor_session_id(0x1234567890abcdefull), "visitor-90abcdef");
  EXPECT_EQ(visitor_session_id(0), "visitor-00000000");
  EXPECT_TRUE(is_visitor_session(visitor_session_id(42)));
  EXPECT_FALSE(is_visitor_session("P01"));
  EXPECT_EQ(utc_date(0), "1970-01-01");
  EXPECT_EQ(utc_date(1795737599), "2026-11-26");  // 23:59:59 UTC: the date only, in UTC
  EXPECT_EQ(utc_date(1795737600), "2026-11-27");
  EXPECT_EQ(visitor_results_file("2026-11-27"), "visitors-2026-11-27.csv");
}

TEST(VisitorOffer, NoOfferWhereItsCuesCannotBeDelivered) {
  StudyProtocol p;
  p.conditions = {StudyCondition::visual_only, StudyCondition::tactile_only, StudyCondition::both};
  EXPECT_EQ(undeliverable_cues(p, true), "");
  EXPECT_EQ(undeliverable_cues(p, false),
            "no audio output, so the taps felt through the stick cannot be given (2 of its 3 conditions); "
            "`mallet doctor` says why there is no sound");
  p.conditions = {StudyCondition::visual_only};
  EXPECT_EQ(undeliverable_cues(p, false), "") << "the bounce alone needs no sound card";
  p.sound = true;
  EXPECT_EQ(undeliverable_cues(p, false), "no audio output, so its sound cannot be played");
}

}  // namespace
}  // namespace mallet::study
