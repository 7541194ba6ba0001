#include "core/study/visitor_offer.hpp"

#include <cstdio>

#include <fmt/format.h>

namespace mallet::study {

bool VisitorOffer::offered(Nanos now) {
  while (now >= next_ + lasts_) next_ += every_;  // offers nobody took
  return now >= next_;
}

std::string visitor_session_id(std::uint64_t random) {
  return fmt::format("visitor-{:08x}", static_cast<unsigned>(random & 0xffffffffu));
}

std::string utc_date(std::time_t t) {
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[16];
  std::strftime(buf, sizeof buf, "%Y-%m-%d", &tm);
  return buf;
}

std::string visitor_results_file(const std::string& date) { return "visitors-" + date + ".csv"; }

}  // namespace mallet::study
