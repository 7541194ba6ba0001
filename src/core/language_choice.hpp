#pragma once
// Which visitor language the kiosk shows now ([kiosk] language, [attract] languages,
// the operator page's L). In Attract the invitation goes through [attract] languages in
// turn, each for language_every_s from the moment Attract began (none listed: the kiosk's
// language); a visitor who starts playing keeps the language on the screen until the next
// Attract. The operator's choice replaces the kiosk's language until the kiosk restarts or a
// reload changes the languages set (the window kiosk makes a new choice only then).
#include <string>
#include <vector>

#include "core/kiosk_states.hpp"
#include "core/time.hpp"

namespace mallet {

class LanguageChoice {
 public:
  LanguageChoice() = default;
  LanguageChoice(std::string kiosk_language, std::vector<std::string> attract_languages, Nanos every);

  //! The language for a frame at `now` in `state`, entered at `since`.
  const std::string& at(KioskState state, Nanos since, Nanos now);
  //! The operator page's L: the language after the one shown, in visitor_languages()'s order.
  const std::string& next();
  const std::string& shown() const { return shown_; }

 private:
  std::string kiosk_ = "en", shown_ = "en";
  std::vector<std::string> attract_;
  Nanos every_ = 1;
};

}  // namespace mallet
