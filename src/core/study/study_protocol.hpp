#pragma once
// A psychophysics protocol for study mode (both papers' stated future work: a perceptual
// evaluation of the visual and tactile vibrations). A protocol names a task, the sensory
// conditions, the stimuli (materials of config/materials.toml, optionally with Eq. 1's
// decay rate B scaled), how often each is shown, and a seed; config/study/example.toml
// documents every key.
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "core/file_error.hpp"
#include "core/material.hpp"
#include "core/enum_names.hpp"
#include "core/study/quest.hpp"
#include "core/study/quest_plus.hpp"
#include "core/study/staircase.hpp"
#include "core/texture_relief.hpp"
#include "core/time.hpp"

namespace mallet::study {

enum class StudyTask {
  two_afc_harder,  //!< "2afc_harder": two taps, which felt harder (answer 1 or 2)
  name_material,   //!< "name_material": one tap, name its material
  //! "texture_slope": the second paper's bump or hole, crossed with the mouse or the remote
  //! (a texture scene); `question` says what is asked.
  texture_slope,
};
inline constexpr EnumNames<StudyTask, 3> kStudyTaskNames{{{StudyTask::two_afc_harder, "2afc_harder"},
                                                         {StudyTask::name_material, "name_material"},
                                                         {StudyTask::texture_slope, "texture_slope"}}};

//! What a texture_slope trial asks: after one crossing, "bump or hole"; after two (of
//! reliefs of the same shape), "which was steeper" (answer 1 or 2: the higher one).
enum class TextureQuestion { bump_or_hole, steeper };
inline constexpr EnumNames<TextureQuestion, 2> kTextureQuestionNames{
    {{TextureQuestion::bump_or_hole, "bump_or_hole"}, {TextureQuestion::steeper, "steeper"}}};

//! What a condition keeps of the stimulus: the visual vibration (Eq. 1, the material's
//! visual triple), the actuator signal (Eq. 1, its actuator triple), both or neither. In a
//! texture_slope task the visual cue is the Speed technique (the cursor's speed follows the
//! slope) and the tactile one the vibrotactile stripes on the actuator.
enum class StudyCondition { visual_only, tactile_only, both, none };

inline constexpr EnumNames<StudyCondition, 4> kStudyConditionNames{
    {{StudyCondition::visual_only, "visual_only"}, {StudyCondition::tactile_only, "tactile_only"},
     {StudyCondition::both, "both"}, {StudyCondition::none, "none"}}};

std::string_view task_name(StudyTask task);
std::string_view condition_name(StudyCondition condition);
std::optional<StudyCondition> condition_from_name(std::string_view name);
inline bool shows_visual(StudyCondition c) { return c == StudyCondition::visual_only || c == StudyCondition::both; }
inline bool plays_actuator(StudyCondition c) { return c == StudyCondition::tactile_only || c == StudyCondition::both; }

//! One stimulus: a material whose two Eq. 1 triples are used as configured, except that
//! B (decay_per_s) of both is multiplied by `decay_scale` (B grows with stiffness in
//! Okamura's model: Table 1 gives metal a larger B than wood).
struct Stimulus {
  std::string name;     //!< unique in the protocol; what the CSV's `stimuli` column shows
  Material material;    //!< name = the base material (the answer of name_material); triples scaled
  double decay_scale = 1.0;
  //! texture_slope: the relief under the disc (its shape and height; the scene's profile,
  //! centre and radius).
  std::optional<TextureRelief> relief;
};

//! Two stimuli compared in a 2AFC trial. `harder` is the one with the larger B; the
//! stimulus difference is 100·(B_harder/B_softer − 1) percent (the same for the visual and
//! the actuator triple when both come from Table 1 and one decay_scale).
struct StimulusPair {
  int a = 0, b = 0;  //!< indices in StudyProtocol::stimuli
  int harder = 0;    //!< a or b
  double difference_pct = 0;
};

//! The simulated clock of one trial (int64 ns): lead, stimulus 1, [gap, stimulus 2], answer.
struct StudyTiming {
  Nanos lead = 500'000'000;              //!< trial start → first stimulus onset
  Nanos stimulus_interval = 1'200'000'000;  //!< onset → onset of the two 2AFC stimuli
  Nanos stimulus = 1'000'000'000;        //!< a stimulus is shown this long before what follows
  Nanos inter_trial = 500'000'000;       //!< answer → next trial start
};

//! How the pairs' differences are chosen: a fixed set shown `repetitions` times each (the
//! method of constant stimuli), or per condition an adaptive track (adaptive_schedule.hpp).
enum class StudyProcedure { constant, staircase, quest, quest_plus };
inline constexpr EnumNames<StudyProcedure, 4> kStudyProcedureNames{{{StudyProcedure::constant, "constant"},
                                                                   {StudyProcedure::staircase, "staircase"},
                                                                   {StudyProcedure::quest, "quest"},
                                                                   {StudyProcedure::quest_plus, "quest_plus"}}};
std::string_view procedure_name(StudyProcedure procedure);

//! How the participant answers: keys (1/2, a material's letter), or by striking one of the
//! answer bars shown beside the stimulus bar with the same mallet.
enum class StudyResponse { keys, strike };
inline constexpr EnumNames<StudyResponse, 2> kStudyResponseNames{
    {{StudyResponse::keys, "keys"}, {StudyResponse::strike, "strike"}}};
std::string_view response_name(StudyResponse response);

//! What an answer strike gives, stated in the protocol so that answers do not
//! contaminate the stimuli: by default a neutral click on the speaker and nothing on the
//! actuator or in the mallet's bounce.
struct AnswerStrike {
  std::string voice = "click";   //!< the instruments file's preset the answer bars sound; empty: silent
  FilePlace voice_at;            //!< where it was set (a voice the scene lacks is reported there)
  std::optional<Material> feel;  //!< Eq. 1's actuator signal and bounce of an answer strike; none: neither
};

//! A visitor study's own words, in one language.
struct VisitorTexts {
  std::string offer;
  std::string consent;
};

//! A visitor micro-study (the kiosk's [study] visitor_protocol): the attract screen's offer,
//! the one-screen consent text a visitor agrees to by striking, how many trials a visitor
//! does, and how long the kiosk waits for a strike before the session counts as abandoned.
//! Its words are written in `language` ([visitor] language, "en" unless set) and may be
//! given in others ([visitor.text.LANG]): a visitor is shown the study in the kiosk's
//! language where the protocol has its words, else wholly in the protocol's own language
//! (the kiosk's texts around them too: never a mix on one screen).
struct VisitorProtocol {
  std::string offer = "Help science: 60 seconds, 6 taps";
  std::string consent;
  std::string language = "en";
  std::vector<std::pair<std::string, VisitorTexts>> texts;  //!< [visitor.text.LANG], file order
  int trials = 6;
  Nanos answer_timeout = 20'000'000'000;

  //! The language a visitor whose kiosk speaks `kiosk_language` is shown the study in.
  std::string language_for(std::string_view kiosk_language) const;
  //! The words in `language` (the protocol's own for its language or one it lacks).
  VisitorTexts text_in(std::string_view language) const;
};

//! The grid an adaptive track's differences are rounded to: each is one generated stimulus,
//! the reference with B larger by that much.
inline constexpr double kAdaptiveGridPct = 0.5;

struct AdaptiveProtocol {
  int reference = 0;          //!< the stimulus every trial compares against (index)
  double min_pct = 0.5, max_pct = 60;  //!< the differences a track may test
  StaircaseRule staircase;    //!< procedure = staircase
  QuestModel quest_model;     //!< procedure = quest
  QuestPrior quest_prior;
  int quest_trials = 40;      //!< per condition
  //! procedure = quest_plus: its curve and grid (the stimuli are the pairs' differences).
  QuestPlusSetup quest_plus;
  int quest_plus_trials = 64;  //!< per condition
};

struct StudyProtocol {
  std::string file;               //!< where it was loaded from (messages)
  std::string name;               //!< CSV column `protocol`
  StudyTask task = StudyTask::two_afc_harder;
  TextureQuestion question = TextureQuestion::bump_or_hole;  //!< texture_slope
  std::vector<StudyCondition> conditions;
  std::vector<Stimulus> stimuli;
  std::vector<StimulusPair> pairs;  //!< 2AFC only
  std::vector<int> named;           //!< name_material: the stimuli shown (indices)
  int repetitions = 2;              //!< per condition × item; even for 2AFC (both orders)
  StudyProcedure procedure = StudyProcedure::constant;
  //! Adaptive procedures: their rules; `pairs` then holds one pair per step of the grid,
  //! (reference, reference with B larger by min_pct + k·kAdaptiveGridPct).
  AdaptiveProtocol adaptive;
  std::uint64_t seed = 1;
  std::string output;               //!< default results CSV (--out overrides)
  double impact_speed_m_per_s = 0.5;
  bool sound = false;               //!< the speaker's note: off, or one note for every stimulus
  int reference_bar = 0;            //!< the bar whose note (and voice) every stimulus uses
  StudyTiming timing;
  StudyResponse response = StudyResponse::keys;
  AnswerStrike answer_strike;  //!< response = strike
  std::optional<VisitorProtocol> visitor;  //!< [visitor]: a protocol the kiosk offers its visitors

  bool texture() const { return task == StudyTask::texture_slope; }
  //! Trials of two stimuli and the answer 1 or 2 (2afc_harder, texture_slope's steeper).
  bool paired() const {
    return task == StudyTask::two_afc_harder || (texture() && question == TextureQuestion::steeper);
  }
  //! Items per condition: pairs (2AFC) or named stimuli.
  std::size_t items() const { return paired() ? pairs.size() : named.size(); }
  //! The answers a participant may give: "1", "2" or the materials' names.
  std::vector<std::string> answer_choices() const;
};

}  // namespace mallet::study
