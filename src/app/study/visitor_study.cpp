#include "app/study/visitor_study.hpp"

#include <ctime>

#include "core/data_paths.hpp"
#include "app/common/settings_source.hpp"
#include "app/study/study_headless.hpp"
#include "app/study/study_stimuli.hpp"
#include "core/config/scene_config.hpp"
#include "core/file_error.hpp"
#include "core/study/balanced_schedule.hpp"
#include "core/study/protocol_loader.hpp"
#include "core/study/visitor_offer.hpp"

namespace mallet::app {

namespace fs = std::filesystem;
using namespace mallet::study;

StudyProtocol load_visitor_protocol(const StudyConfig& config, const Scene& base) {
  StudyProtocol protocol = load_study_protocol(config.visitor_protocol, base.materials, base.targets.size());
  if (!protocol.visitor)
    throw FileError(config.visitor_protocol_at, "names " + config.visitor_protocol +
                                                    ", which has no [visitor] table (config/study/visitor.toml has one)");
  return protocol;
}

fs::path visitor_results_dir(const StudyConfig& config) {
  return config.results_dir.empty() ? state_dir() / "visitor-study" : fs::path(config.results_dir);
}

StudyPlan plan_visitor(const AppConfig& config, const Scene& base, const StudyProtocol& protocol, const fs::path& dir,
                       const std::string& id, const std::string& date) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error(dir.string() + ": cannot create the visitors' results folder: " + ec.message());
  StudyPlan plan = plan_session(config, base, protocol, id, dir / visitor_results_file(date));
  plan.max_trials = protocol.visitor ? protocol.visitor->trials : 0;
  plan.session = date;
  return plan;
}

study::VisitorSessionResult run_visitor_session(const StudyPlan& plan, const Scene& scene, StudyStage& stage,
                                         VisitorAnswers& answers) {
  study::VisitorSessionResult result;
  result.id = plan.participant;
  result.planned = plan.planned_trials();
  result.csv = plan.csv;
  const std::optional<bool> agreed = answers.consent(*plan.protocol.visitor, stage.now());
  if (!agreed) {
    result.abandoned = true;
    return result;
  }
  if (!*agreed) return result;
  result.consented = true;
  const StudyRunResult run = run_session(plan, scene, stage, answers);
  result.answered = run.answered;
  result.abandoned = run.answered < result.planned;
  return result;
}

namespace {

//! A simulated visitor: agrees (or declines) by striking "1" (yes) or "2" (no) 2 s after the
//! consent screen opens, answers as the simulated observer does, and walks away after
//! `abandon_after` trials (0: never): the kiosk then waits the answer timeout in vain.
class SimulatedVisitor final : public VisitorAnswers {
 public:
  SimulatedVisitor(const StudyPlan& plan, StudyStage& stage, const Scene& scene, bool agrees, int abandon_after)
      : stage_(stage), scene_(scene), bars_(answer_bars(scene, plan.protocol)), observer_(plan, {}, true),
        strikes_(observer_, stage, scene, plan.protocol), speed_(plan.protocol.impact_speed_m_per_s),
        timeout_(plan.protocol.visitor->answer_timeout), agrees_(agrees), abandon_after_(abandon_after) {}
  std::optional<bool> consent(const VisitorProtocol&, Nanos opens) override {
    constexpr Nanos kReading = 2 * kNanosPerSecond;
    const TrialAnswer a = strike_answer_bar(stage_, scene_, bars_, agrees_ ? 0 : 1, opens + kReading, opens, speed_);
    return a.answer == bars_.at(0).answer;
  }
  std::optional<TrialAnswer> answer(const ScheduledTrial& trial, Nanos opens) override {
    if (abandon_after_ > 0 && answered_ == abandon_after_) {
      stage_.wait_until(opens + timeout_);  // nobody strikes: the kiosk gives up
      return std::nullopt;
    }
    ++answered_;
    return strikes_.answer(trial, opens);
  }
  std::string name() const override { return "strike"; }

 private:
  StudyStage& stage_;
  const Scene& scene_;
  std::vector<AnswerBar> bars_;
  ScriptedAnswers observer_;
  StrikeAnswers strikes_;
  double speed_;
  Nanos timeout_;
  bool agrees_;
  int abandon_after_;
  int answered_ = 0;
};

}  // namespace

std::vector<study::VisitorSessionResult> run_simulated_visitors(const SimulatedVisitors& o) {
  const AppConfig config = command_settings(o.config, o.config_dir, "study");
  const Scene base = config::load_scene(o.scene);
  StudyConfig where;
  where.visitor_protocol = o.protocol.string();
  where.visitor_protocol_at = {"--protocol", 0, 0};
  const StudyProtocol protocol = load_visitor_protocol(where, base);
  const std::string date = o.date.empty() ? utc_date(std::time(nullptr)) : o.date;
  SplitMix64 ids(o.seed);
  std::vector<study::VisitorSessionResult> out;
  for (int k = 1; k <= o.visitors; ++k) {
    const StudyPlan plan = plan_visitor(config, base, protocol, o.out_dir, visitor_session_id(ids.next()), date);
    const Scene scene = make_study_scene(plan.base, plan.protocol);
    HeadlessStage stage(scene, plan, std::nullopt);
    const bool agrees = o.decline_every <= 0 || k % o.decline_every != 0;
    SimulatedVisitor visitor(plan, stage, scene, agrees, k % 2 == 0 ? o.abandon_after : 0);
    out.push_back(run_visitor_session(plan, scene, stage, visitor));
    stage.finish();
  }
  return out;
}

}  // namespace mallet::app
