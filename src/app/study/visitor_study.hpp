#pragma once
// The visitor micro-study (issue: research at the kiosk): a museum's visitors as willing
// participants, opt-in and anonymous. The kiosk's [study] visitor_protocol names a study
// protocol with a [visitor] table and response = "strike"; from time to time the attract
// screen offers it (study::VisitorOffer); a visitor who strikes "Yes" sees the protocol's
// one-screen consent text and agrees (or not) by striking, then does the protocol's few
// trials by striking, like any participant (run_session: the same trials, rows and
// durability).
//
// What is kept of a visitor: a random session id as the participant ("visitor-1f3a9c0e"),
// the date (UTC) as the `session`, and the answers. Nothing else: no time of day, no name.
// The rows go to DIR/visitors-YYYY-MM-DD.csv, appended and fsync'd row by row. A visitor who
// walks away (no strike for the protocol's answer_timeout_s) leaves the trials done in the
// file; `mallet study summary` counts completed and abandoned visitor sessions from their
// rows' planned_trials.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "app/study/study_session.hpp"
#include "core/study/visitor_offer.hpp"
#include "core/study/study_protocol.hpp"

namespace mallet::app {

//! A visitor's answers: their consent and the trials' answers, by striking.
class VisitorAnswers : public AnswerSource {
 public:
  //! The consent screen, open from `opens`: true when the visitor strikes "Yes", false for
  //! "No", nothing when they walk away (no strike within the answer timeout) or stop.
  virtual std::optional<bool> consent(const study::VisitorProtocol& visitor, Nanos opens) = 0;
};

//! A visitor protocol loaded against the kiosk's scene: FileError naming the file (and the
//! settings' line that names it) when it does not load or has no [visitor] table.
study::StudyProtocol load_visitor_protocol(const StudyConfig& config, const Scene& base);

//! The results folder: [study] results_dir, else the state folder's visitor-study/.
std::filesystem::path visitor_results_dir(const StudyConfig& config);

//! One visitor's plan: `protocol`'s schedule for `id`, its first [visitor] trials, its rows
//! to DIR/visitors-DATE.csv with session = DATE.
StudyPlan plan_visitor(const AppConfig& config, const Scene& base, const study::StudyProtocol& protocol,
                       const std::filesystem::path& dir, const std::string& id, const std::string& date);

//! The consent, then the trials. `study_scene` = make_study_scene(plan.base, plan.protocol)
//! (in a window: study_scene_for, laid out for its shape).
study::VisitorSessionResult run_visitor_session(const StudyPlan& plan, const Scene& study_scene, StudyStage& stage,
                                         VisitorAnswers& answers);

//! `mallet study visitors --headless`: simulated visitors on the simulated clock, each
//! striking through the kiosk's strike route: they agree (or, with `decline_every` = k,
//! every k-th declines), answer as the simulated observer does, and (with `abandon_after`
//! = n) every other one walks away after n trials.
struct SimulatedVisitors {
  std::filesystem::path protocol;
  std::filesystem::path scene;
  std::optional<std::filesystem::path> config, config_dir;
  std::filesystem::path out_dir;  //!< the day files' folder
  int visitors = 1;
  int abandon_after = 0;  //!< 0: nobody walks away
  int decline_every = 0;  //!< 0: everybody agrees
  std::uint64_t seed = 0; //!< the session ids' generator
  std::string date;       //!< the day (UTC); empty: today
};
std::vector<study::VisitorSessionResult> run_simulated_visitors(const SimulatedVisitors& options);

}  // namespace mallet::app
