#include "core/study/study_protocol.hpp"

#include <algorithm>

namespace mallet::study {

std::string_view task_name(StudyTask task) { return name_in(kStudyTaskNames, task); }

std::string_view condition_name(StudyCondition condition) { return name_in(kStudyConditionNames, condition); }

std::optional<StudyCondition> condition_from_name(std::string_view name) {
  return value_named(kStudyConditionNames, name);
}

std::vector<std::string> StudyProtocol::answer_choices() const {
  if (paired()) return {"1", "2"};
  if (texture()) return {"bump", "hole"};
  std::vector<std::string> out;
  for (int i : named) {
    const std::string& m = stimuli[static_cast<std::size_t>(i)].material.name;
    if (std::find(out.begin(), out.end(), m) == out.end()) out.push_back(m);
  }
  return out;
}

std::string_view response_name(StudyResponse response) { return name_in(kStudyResponseNames, response); }

std::string_view procedure_name(StudyProcedure procedure) {
  return name_in(kStudyProcedureNames, procedure, "constant");
}

std::string VisitorProtocol::language_for(std::string_view kiosk_language) const {
  for (const auto& [lang, words] : texts)
    if (lang == kiosk_language) return lang;
  return language;
}

VisitorTexts VisitorProtocol::text_in(std::string_view lang) const {
  for (const auto& [l, words] : texts)
    if (l == lang) return words;
  return {offer, consent};
}

}  // namespace mallet::study
