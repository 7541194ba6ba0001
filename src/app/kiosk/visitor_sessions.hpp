#pragma once
// The visitor micro-study ([study] visitor_protocol) as the kiosk asks for it. `mallet run`
// (cli/cmd_run.cpp) fills it from the study product (study/visitor_study.hpp,
// study/study_window.hpp), so the kiosk includes nothing of the study's own. Left empty,
// the kiosk offers no study.
#include <functional>
#include <string>
#include <vector>

#include "core/app_config.hpp"
#include "core/pointer_sample.hpp"
#include "core/scene.hpp"
#include "core/study/study_protocol.hpp"
#include "core/study/visitor_offer.hpp"
#include "render/render_setup.hpp"

namespace mallet::app {

struct VisitorSessions {
  //! The protocol, checked against the kiosk's scene; throws naming its file and line.
  std::function<study::StudyProtocol(const StudyConfig& config, const Scene& scene)> load;
  //! One visitor's session, `id` on `date` (UTC), in the kiosk's own window: see
  //! study_window.hpp, run_visitor_window, for `pointer` and `each_frame`.
  std::function<study::VisitorSessionResult(
      render::ProductWindow& window, const AppConfig& config, const Scene& scene, const study::StudyProtocol& protocol,
      const std::string& id, const std::string& date, std::function<std::vector<PointerSample>()> pointer,
      std::function<bool()> each_frame)>
      run;

  explicit operator bool() const { return load && run; }
};

}  // namespace mallet::app
