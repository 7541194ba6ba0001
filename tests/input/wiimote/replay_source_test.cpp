// Recorded reports played back: the same parser and tracker as live, the recorded times,
// a live session → recording → replay round trip that gives back the same LED track, and
// the dots of a replay equal to what `mallet wiimote decode` prints for the same bytes.
#include "input/wiimote/replay_source.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

#include "run_cli.hpp"
#include "fake_remote.hpp"
#include "input/wiimote/wiimote_device.hpp"
#include "test_paths.hpp"

namespace mallet::input::wiimote {
namespace {

using namespace test;

constexpr Nanos kT0 = 5 * kNanosPerSecond;

std::string recording_text(const std::vector<std::pair<Nanos, Bytes>>& reports) {
  std::ostringstream out;
  ReplayWriter writer(out);
  for (const auto& [t, bytes] : reports) writer.write(t, bytes);
  return out.str();
}

//! A still LED, a status report, a 300 ms gap, the LED elsewhere, a junk report.
std::vector<std::pair<Nanos, Bytes>> session() {
  std::vector<std::pair<Nanos, Bytes>> r;
  for (int i = 0; i < 20; ++i) r.emplace_back(kT0 + i * 10 * kMs, ir_report({{512, 384, 3}, {40, 700, 1}}));
  r.emplace_back(kT0 + 195 * kMs, status_report(0x99));
  r.emplace_back(kT0 + 500 * kMs, ir_report({{700, 100, 5}}));
  r.emplace_back(kT0 + 505 * kMs, Bytes{0x33, 0x00});  // truncated
  r.emplace_back(kT0 + 510 * kMs, ir_report({{702, 101, 5}}));
  return r;
}

TEST(ReplaySource, PlaysTheRecordingThroughTheParserAndTrackerWithItsTimes) {
  ReplaySource source(parse_replay(recording_text(session()), "session.replay"));
  EXPECT_EQ(source.size(), 24u);
  EXPECT_EQ(*source.next_time(), kT0);
  std::vector<ReportOutcome> out;
  while (auto o = source.next()) out.push_back(*o);
  ASSERT_EQ(out.size(), 25u);  // 24 reports and one time-out
  for (int i = 0; i < 20; ++i) {
    const ReportOutcome& o = out[static_cast<std::size_t>(i)];
    ASSERT_EQ(o.kind, ReportOutcome::Kind::ir) << i;
    EXPECT_EQ(o.t_ns, kT0 + i * 10 * kMs) << i;
    EXPECT_EQ(o.frame->t_ns, o.t_ns) << i;
    ASSERT_TRUE(o.update.point) << i;
    EXPECT_EQ(o.update.point->x, 512.0) << i;  // the largest dot, not the reflection
    EXPECT_EQ(o.update.point->t_ns, o.t_ns) << i;
    EXPECT_EQ(o.update.event, i == 0 ? IrTrackerEvent::regained : IrTrackerEvent::none) << i;
  }
  EXPECT_EQ(out[20].kind, ReportOutcome::Kind::status);
  EXPECT_EQ(out[20].status->battery, 0x99);
  EXPECT_EQ(out[21].kind, ReportOutcome::Kind::timeout);  // 150 ms without a dot
  EXPECT_EQ(out[21].update.event, IrTrackerEvent::lost);
  EXPECT_EQ(out[21].t_ns, kT0 + 500 * kMs);
  EXPECT_EQ(out[22].update.event, IrTrackerEvent::regained);
  EXPECT_EQ(out[22].update.point->x, 700.0);
  EXPECT_EQ(out[23].kind, ReportOutcome::Kind::malformed);
  EXPECT_EQ(out[23].error->message(), "report 0x33 must be 18 bytes (id included), got 2");
  EXPECT_EQ(out[24].update.point->x, 702.0);
  EXPECT_EQ(out[24].update.event, IrTrackerEvent::none);
  const RemoteStats& stats = source.tracker().stats();
  EXPECT_EQ(stats.reports, 24u);
  EXPECT_EQ(stats.ir_reports, 22u);
  EXPECT_EQ(stats.malformed, 1u);
  EXPECT_EQ(*stats.battery, 0x99);
  EXPECT_TRUE(source.done());
  EXPECT_FALSE(source.next());
}

TEST(ReplaySource, ALiveSessionRecordedAndReplayedGivesTheSameLedTrack) {
  FakeClock clock;
  FakeFinder finder(clock);
  auto remote = finder.add("/dev/hidraw0");
  WiimoteDeviceConfig config;
  config.keep_raw_reports = true;
  WiimoteDevice device(finder, clock, config);
  remote->send_ir(30, 100, 600, 7, -5);
  remote->send(status_report(0x77), 3 * kMs);
  remote->send_ir(30, 310, 450, -3, 2);
  for (int i = 0; i < 100'000 && !remote->script.empty(); ++i) device.step();
  ASSERT_TRUE(remote->script.empty());
  std::vector<LedSample> live;
  device.drain(live);
  std::vector<RawReport> raw;
  device.drain_raw(raw);
  ASSERT_EQ(raw.size(), remote->delivered.size());

  std::ostringstream text;
  ReplayWriter writer(text);
  for (const RawReport& r : raw) writer.write(r.t_ns, r.span());
  ReplaySource replay(parse_replay(text.str(), "live.replay"));
  std::vector<LedSample> replayed;
  while (auto o = replay.next())
    if (o->update.point || o->update.event != IrTrackerEvent::none)
      replayed.push_back({o->t_ns, o->update.event, o->update.point.has_value(),
                          o->update.point.value_or(IrPoint{})});
  ASSERT_EQ(replayed.size(), live.size());
  ASSERT_EQ(live.size(), 60u);
  for (std::size_t i = 0; i < live.size(); ++i) {
    EXPECT_EQ(replayed[i].t_ns, live[i].t_ns) << i;
    EXPECT_EQ(replayed[i].event, live[i].event) << i;
    EXPECT_EQ(replayed[i].point.x, live[i].point.x) << i;
    EXPECT_EQ(replayed[i].point.y, live[i].point.y) << i;
    EXPECT_EQ(replayed[i].point.size, live[i].point.size) << i;
  }
  EXPECT_EQ(*replay.tracker().stats().battery, 0x77);
  EXPECT_EQ(replay.tracker().stats().ir_reports, device.state().remote.ir_reports);
}

TEST(ReplaySource, DotsEqualWhatWiimoteDecodePrints) {
  std::vector<std::pair<Nanos, Bytes>> reports = session();
  reports.erase(reports.begin() + 22);  // decode refuses the truncated report (it exits 2)
  reports.emplace_back(kT0 + 600 * kMs, ack_report(0x16));
  // Basic IR (0x36): two pairs of dots in 5 bytes each, then 9 extension bytes.
  reports.emplace_back(kT0 + 610 * kMs, Bytes{0x36, 0x00, 0x00, 0xff, 0xff, 0xb9, 0x2c, 0xbc, 0xff, 0xff, 0xf0, 0x01,
                                              0x02, 0, 0, 0, 0, 0, 0, 0, 0, 0});
  reports.emplace_back(kT0 + 620 * kMs, ir_report({{0, 0, 0}, {1023, 767, 15}, {1, 766, 7}}));
  const auto dir = mallet::test::scratch_dir();
  std::ofstream(dir / "session.replay") << recording_text(reports);
  std::string hex;
  for (const auto& [t, bytes] : reports) hex += to_hex(bytes) + "\n";
  std::ofstream(dir / "session.hex") << hex;

  ReplaySource source = ReplaySource::open(dir / "session.replay");
  std::string replayed;
  while (auto o = source.next())
    if (o->frame) replayed += format_ir_slots(o->frame->slots) + "\n";
  const auto decoded = mallet::test::run_mallet("wiimote decode --hex " + (dir / "session.hex").string());
  ASSERT_EQ(decoded.status, 0) << decoded.output;
  EXPECT_EQ(replayed, decoded.output);
  EXPECT_NE(decoded.output.find("512,384,3 40,700,1 - -\n"), std::string::npos) << decoded.output;
  EXPECT_NE(decoded.output.find("1023,767,? 300,700,? - 1,2,?\n"), std::string::npos) << decoded.output;
  EXPECT_NE(decoded.output.find("0,0,0 1023,767,15 1,766,7 -\n"), std::string::npos) << decoded.output;
}

TEST(ReplaySource, AMalformedRecordingNamesItsLine) {
  const auto dir = mallet::test::scratch_dir();
  std::ofstream(dir / "bad.replay") << "# mallet-wiimote-replay 1\n100 33 00\n50 33 00\n";
  const FileError e = mallet::test::file_error_of([&] { ReplaySource::open(dir / "bad.replay"); });
  EXPECT_EQ(e.line(), 3u);
}

}  // namespace
}  // namespace mallet::input::wiimote
