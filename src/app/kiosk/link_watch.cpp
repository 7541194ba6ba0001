#include "app/kiosk/link_watch.hpp"

namespace mallet::app {

std::vector<LinkChange> LinkWatch::look(const IrLink& link) {
  std::vector<LinkChange> changes;
  if (link.up != up_) {
    changes.push_back(link.up ? LinkChange{true, {}} : LinkChange{false, link.problem});
  } else if (link.up && link.drops != drops_) {
    // Gone and back since the last look: however many drops, one loss (the last one's reason).
    changes.push_back({false, link.last_drop});
    changes.push_back({true, {}});
  }
  up_ = link.up;
  drops_ = link.drops;
  return changes;
}

}  // namespace mallet::app
