#include "core/language_choice.hpp"

#include <algorithm>

#include "core/visitor_language.hpp"

namespace mallet {

LanguageChoice::LanguageChoice(std::string kiosk_language, std::vector<std::string> attract_languages, Nanos every)
    : kiosk_(std::move(kiosk_language)), shown_(kiosk_), attract_(std::move(attract_languages)),
      every_(std::max<Nanos>(every, 1)) {}

const std::string& LanguageChoice::at(KioskState state, Nanos since, Nanos now) {
  if (state != KioskState::attract) return shown_;
  if (attract_.empty()) return shown_ = kiosk_;
  const Nanos turn = std::max<Nanos>(now - since, 0) / every_;
  return shown_ = attract_[static_cast<std::size_t>(turn % static_cast<Nanos>(attract_.size()))];
}

const std::string& LanguageChoice::next() {
  const std::vector<std::string> all = visitor_languages();
  const auto it = std::find(all.begin(), all.end(), shown_);
  kiosk_ = it == all.end() || it + 1 == all.end() ? all.front() : *(it + 1);
  return shown_ = kiosk_;
}

}  // namespace mallet
