#pragma once
// The visitor micro-study's timing and anonymity, as pure functions of the clock (the
// kiosk's, int64 ns) and of a random number, so that a test can drive them.
//
// The offer: from `every` after the kiosk starts, and every `every` after that, the attract
// screen offers the study for `lasts`; a visitor who is playing then sees it too. A session
// (accepted or not) moves the next offer to `every` after its end, so a queue of visitors is
// not asked again and again.
//
// Anonymity: a visitor is a random session id ("visitor-" and 8 hex digits) and the date
// (UTC, no time of day); their rows go to one file a day, visitors-YYYY-MM-DD.csv.
#include <cstdint>
#include <ctime>
#include <filesystem>
#include <string>

#include "core/time.hpp"

namespace mallet::study {

class VisitorOffer {
 public:
  VisitorOffer(Nanos every, Nanos lasts, Nanos start) : every_(every), lasts_(lasts), next_(start + every) {}
  //! Whether the offer is on the screen at `now` (moves on past offers that went unanswered).
  bool offered(Nanos now);
  //! A session ended at `now`: the next offer comes `every` later.
  void session_ended(Nanos now) { next_ = now + every_; }
  Nanos next_offer() const { return next_; }

 private:
  Nanos every_, lasts_, next_;
};

//! A visitor micro-study's participant: "visitor-" and a random id.
inline bool is_visitor_session(const std::string& participant) { return participant.starts_with("visitor-"); }
//! "visitor-" and the low 32 bits of `random` as 8 hex digits.
std::string visitor_session_id(std::uint64_t random);
//! The UTC date of a wall-clock time: "YYYY-MM-DD".
std::string utc_date(std::time_t t);
//! "visitors-YYYY-MM-DD.csv".
std::string visitor_results_file(const std::string& date);

struct StudyProtocol;

//! Why the kiosk cannot deliver a visitor protocol's cues ("" when it can): without an audio
//! output, a condition that plays the actuator (tactile_only, both) would give no cue at all
//! and its answers would be written as data, and a protocol with sound would be silent. The
//! kiosk then makes no offer and says why.
std::string undeliverable_cues(const StudyProtocol& protocol, bool audio_output);

//! How one visitor's session ended, as the kiosk counts it and the log says it.
struct VisitorSessionResult {
  std::string id;
  bool consented = false;
  bool abandoned = false;  //!< walked away: at the consent, or before the last trial
  int planned = 0;
  int answered = 0;
  std::filesystem::path csv;
};

}  // namespace mallet::study
