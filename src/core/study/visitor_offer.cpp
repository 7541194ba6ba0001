#include "core/study/visitor_offer.hpp"

#include <cstdio>

#include <fmt/format.h>

#include "core/study/study_protocol.hpp"

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

std::string undeliverable_cues(const StudyProtocol& protocol, bool audio_output) {
  if (audio_output) return {};
  std::size_t felt = 0;
  for (const StudyCondition c : protocol.conditions)
    if (plays_actuator(c)) ++felt;
  // In an operator's words: what a visitor would miss, not the protocol's condition names.
  if (felt > 0)
    return "no audio output, so the taps felt through the stick cannot be given (" + std::to_string(felt) + " of its " +
           std::to_string(protocol.conditions.size()) + " conditions); `mallet doctor` says why there is no sound";
  if (protocol.sound) return "no audio output, so its sound cannot be played";
  return {};
}

}  // namespace mallet::study
