#include "app/bench/bench_latency_strokes.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <utility>

#include "input/wiimote/reports.hpp"

namespace mallet::app::latency {

Nanos Hand::move(double x_m, double y_m, int* row_out) const {
  const int col = static_cast<int>(std::lround(rig.map.col_of_x(x_m)));
  const int row = std::clamp(static_cast<int>(std::lround(rig.map.row_of_y(y_m))), 0, kHeight - 1);
  if (row_out) *row_out = row;
  return rig.hand->move_to(col, row);
}

Nanos mouse_stroke(const Rig& rig, const Bar& b, double v, const std::function<void()>& on_hold) {
  const Hand hand{rig};
  const double top = b.contact_y_m + kAboveM, bottom = b.contact_y_m - kBelowM;
  hand.move(b.x_m, top);
  sleep_ms(15);
  hand.move(b.x_m, top);
  sleep_ms(150);
  std::vector<std::pair<Nanos, double>> path;  // (when sent, world y the kiosk sees)
  const Nanos t0 = monotonic_now() + kMs;
  for (int k = 0;; ++k) {
    const Nanos due = t0 + k * kMs;
    const double y = std::max(bottom, top - v * to_seconds(due - t0));
    sleep_until(due);
    int row = 0;
    const Nanos sent = hand.move(b.x_m, y, &row);
    path.emplace_back(sent, rig.map.y_of_row(row));
    if (y <= bottom) break;
  }
  // The crossing of the contact plane, interpolated between the two events around it.
  Nanos contact = -1;
  for (std::size_t k = 1; k < path.size() && contact < 0; ++k) {
    const auto [ta, ya] = path[k - 1];
    const auto [tb, yb] = path[k];
    if (ya > b.contact_y_m && yb <= b.contact_y_m)
      contact =
          ta + static_cast<Nanos>(std::llround((ya - b.contact_y_m) / (ya - yb) * static_cast<double>(tb - ta)));
  }
  sleep_ms(80);
  if (on_hold) on_hold();
  for (int k = 1; k <= 20; ++k) {  // back up at ≈1 m/s
    hand.move(b.x_m, bottom + (top - bottom) * k / 20.0);
    sleep_ms(3.5);
  }
  return contact;
}

RemoteScript write_remote_script(const Rig& rig, const std::filesystem::path& file, int strokes, Nanos lead) {
  struct Stroke {
    Nanos start;
    int bar;
    double v;
  };
  std::vector<Stroke> plan;
  RemoteScript script;
  for (int k = 0; k < strokes; ++k) {
    const Nanos start = lead + k * 600 * kMs + (k * 3'300'000) % (10 * kMs);
    const int bar = k % 2;
    const double v = stroke_speed(k);
    plan.push_back({start, bar, v});
    script.contacts.push_back({start + static_cast<Nanos>(std::llround(kAboveM / v * 1e9)), bar, v});
  }
  script.first_stroke = plan.empty() ? lead : plan.front().start;
  script.end = lead + strokes * 600 * kMs + 300 * kMs;
  // The hand at t: hovering above the bar of the stroke to come (moving over in 100 ms,
  // 250 ms before it), or in a stroke: down at v to kBelowM under the contact plane, held
  // 80 ms, back up in 70 ms.
  auto hand_at = [&](Nanos t) -> Vec2 {
    std::size_t next = 0;
    while (next < plan.size() && plan[next].start <= t) ++next;
    if (next > 0) {  // in or after stroke next − 1
      const Stroke& s = plan[next - 1];
      const Bar& b = rig.bars[static_cast<std::size_t>(s.bar)];
      const double top = b.contact_y_m + kAboveM, bottom = b.contact_y_m - kBelowM;
      const Nanos down = static_cast<Nanos>(std::llround((top - bottom) / s.v * 1e9));
      const Nanos since = t - s.start;
      if (since < down) return {b.x_m, top - s.v * to_seconds(since)};
      if (since < down + 80 * kMs) return {b.x_m, bottom};
      if (since < down + 150 * kMs) return {b.x_m, bottom + (top - bottom) * to_seconds(since - down - 80 * kMs) / 0.07};
    }
    const Bar& to = rig.bars[static_cast<std::size_t>(next < plan.size() ? plan[next].bar : 0)];
    const Bar& from = rig.bars[static_cast<std::size_t>(next > 0 ? plan[next - 1].bar : 0)];
    const Nanos move_at = (next < plan.size() ? plan[next].start : script.end) - 250 * kMs;
    const double f = std::clamp(to_seconds(t - move_at) / 0.1, 0.0, 1.0);
    // A visitor arrives: a 1 cm sway (past the kiosk's dead band, so it leaves the attract
    // mode and its ghost stops playing), whole periods ending 2 s before the first stroke.
    const double sway =
        t < lead - 2 * kNanosPerSecond ? 0.01 * std::sin(2 * M_PI * to_seconds(t) / 2.0) : 0.0;
    return {from.x_m + (to.x_m - from.x_m) * f + sway, to.contact_y_m + kAboveM};
  };
  std::ofstream out(file);
  input::wiimote::ReplayWriter writer(out);
  for (Nanos t = 0; t <= script.end; t += 10 * kMs) {
    const Vec2 screen = rig.scene.screen_to_world.unmap(hand_at(t));
    const int cx = std::clamp(static_cast<int>(std::lround((1.0 - screen.x) * 1023)), 0, 1023);
    const int cy = std::clamp(static_cast<int>(std::lround(screen.y * 767)), 0, 767);
    writer.write(t, input::wiimote::extended_ir_report(cx, cy));
  }
  out.close();
  if (!out) throw std::runtime_error("bench latency: cannot write " + file.string());
  return script;
}

}  // namespace mallet::app::latency
