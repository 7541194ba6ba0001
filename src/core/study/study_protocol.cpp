#include "core/study/study_protocol.hpp"

#include <algorithm>

namespace mallet::study {

std::string_view task_name(StudyTask task) {
  switch (task) {
    case StudyTask::two_afc_harder: return "2afc_harder";
    case StudyTask::name_material: return "name_material";
    case StudyTask::texture_slope: return "texture_slope";
  }
  return "?";
}

std::string_view condition_name(StudyCondition condition) {
  switch (condition) {
    case StudyCondition::visual_only: return "visual_only";
    case StudyCondition::tactile_only: return "tactile_only";
    case StudyCondition::both: return "both";
    case StudyCondition::none: return "none";
  }
  return "?";
}

std::optional<StudyCondition> condition_from_name(std::string_view name) {
  for (StudyCondition c : kAllConditions)
    if (condition_name(c) == name) return c;
  return std::nullopt;
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

std::string_view response_name(StudyResponse response) {
  return response == StudyResponse::strike ? "strike" : "keys";
}

std::string_view procedure_name(StudyProcedure procedure) {
  switch (procedure) {
    case StudyProcedure::constant: return "constant";
    case StudyProcedure::staircase: return "staircase";
    case StudyProcedure::quest: return "quest";
  }
  return "constant";
}

}  // namespace mallet::study
