// The kiosk's metrics in Prometheus' text format: counters, histograms with cumulative
// `le` buckets, label escaping, and the visitor sessions and lost tracking the kiosk loop
// derives from its states. No device: the model is fed by hand.
#include <limits>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "core/kiosk_metrics.hpp"

namespace mallet {
namespace {

constexpr Nanos kMillisecond = 1'000'000;
constexpr Nanos kS = kNanosPerSecond;

bool has_line(const std::string& text, const std::string& line) {
  std::istringstream in(text);
  for (std::string l; std::getline(in, l);)
    if (l == line) return true;
  return false;
}

TEST(KioskMetrics, LabelValuesEscapeBackslashQuoteAndLineFeed) {
  EXPECT_EQ(escape_label_value("wood"), "wood");
  EXPECT_EQ(escape_label_value("a\\b"), "a\\\\b");
  EXPECT_EQ(escape_label_value("say \"hi\""), "say \\\"hi\\\"");
  EXPECT_EQ(escape_label_value("two\nlines"), "two\\nlines");
  EXPECT_EQ(escape_label_value("Glöckchen"), "Glöckchen");  // UTF-8 passes as it is

  KioskMetrics m;
  m.strikes[{"x\"y", "a\\b\nc"}] = 3;
  EXPECT_TRUE(has_line(render_prometheus_text(m), "mallet_strikes_total{instrument=\"x\\\"y\",material=\"a\\\\b\\nc\"} 3"))
      << render_prometheus_text(m);
}

TEST(KioskMetrics, SampleValuesAreShortestRoundTripAndNamedSpecials) {
  EXPECT_EQ(format_sample_value(0.0167), "0.0167");
  EXPECT_EQ(format_sample_value(15), "15");
  EXPECT_EQ(format_sample_value(std::numeric_limits<double>::quiet_NaN()), "NaN");
  EXPECT_EQ(format_sample_value(std::numeric_limits<double>::infinity()), "+Inf");
  EXPECT_EQ(format_sample_value(-std::numeric_limits<double>::infinity()), "-Inf");
}

TEST(KioskMetrics, HistogramBucketsAreCumulativeWithInfSumAndCount) {
  DurationHistogram h({10 * kMillisecond, 20 * kMillisecond, 50 * kMillisecond});
  for (Nanos d : {5 * kMillisecond, 10 * kMillisecond, 15 * kMillisecond, 49 * kMillisecond, 400 * kMillisecond, -3 * kMillisecond}) h.observe(d);
  // `le` is "less than or equal": 10 ms falls in the 10 ms bucket; a negative duration is 0.
  EXPECT_EQ(h.cumulative(0), 3u);
  EXPECT_EQ(h.cumulative(1), 4u);
  EXPECT_EQ(h.cumulative(2), 5u);
  EXPECT_EQ(h.cumulative(3), 6u);  // +Inf
  EXPECT_EQ(h.count(), 6u);
  EXPECT_EQ(h.sum_ns(), 479 * kMillisecond);
  EXPECT_THROW(DurationHistogram({20 * kMillisecond, 10 * kMillisecond}), std::invalid_argument);
  EXPECT_THROW(DurationHistogram({0}), std::invalid_argument);
}

TEST(KioskMetrics, FrameHistogramRendersEveryBucketThenInfSumAndCount) {
  KioskMetrics m;
  m.count_frame(16'700'000);
  m.count_frame(16'600'000);
  m.count_frame(40 * kMillisecond);
  const std::string text = render_prometheus_text(m);
  EXPECT_TRUE(has_line(text, "# TYPE mallet_frame_seconds histogram")) << text;
  EXPECT_TRUE(has_line(text, "mallet_frame_seconds_bucket{le=\"0.012\"} 0")) << text;
  EXPECT_TRUE(has_line(text, "mallet_frame_seconds_bucket{le=\"0.0167\"} 2")) << text;
  EXPECT_TRUE(has_line(text, "mallet_frame_seconds_bucket{le=\"0.0334\"} 2")) << text;
  EXPECT_TRUE(has_line(text, "mallet_frame_seconds_bucket{le=\"0.05\"} 3")) << text;
  EXPECT_TRUE(has_line(text, "mallet_frame_seconds_bucket{le=\"+Inf\"} 3")) << text;
  EXPECT_TRUE(has_line(text, "mallet_frame_seconds_sum 0.0733")) << text;
  EXPECT_TRUE(has_line(text, "mallet_frame_seconds_count 3")) << text;
  EXPECT_TRUE(has_line(text, "mallet_frames_total 3")) << text;
  // The +Inf bucket follows the finite ones, and _sum and _count follow the buckets.
  EXPECT_LT(text.find("le=\"1\""), text.find("le=\"+Inf\"", text.find("mallet_frame_seconds_bucket")));
  EXPECT_LT(text.find("mallet_frame_seconds_bucket{le=\"+Inf\"}"), text.find("mallet_frame_seconds_sum"));
}

TEST(KioskMetrics, EveryFamilyHasHelpAndTypeAndUnitsInItsName) {
  KioskMetrics m;
  m.version = "0.1.0";
  const std::string text = render_prometheus_text(m);
  const std::pair<const char*, const char*> families[] = {
      {"mallet_strikes_total", "counter"},
      {"mallet_visitor_sessions_total", "counter"},
      {"mallet_visitor_session_seconds", "histogram"},
      {"mallet_visitor_study_sessions_total", "counter"},
      {"mallet_frames_total", "counter"},
      {"mallet_frame_seconds", "histogram"},
      {"mallet_audio_xruns_total", "counter"},
      {"mallet_audio_output_latency_seconds", "gauge"},
      {"mallet_render_device_lost_total", "counter"},
      {"mallet_vulkan_device_memory_bytes", "gauge"},
      {"mallet_remote_connected", "gauge"},
      {"mallet_remote_battery_ratio", "gauge"},
      {"mallet_tracking_lost_seconds_total", "counter"},
      {"mallet_settings_refused", "gauge"},
      {"mallet_state_folder_writable", "gauge"},
      {"mallet_state", "gauge"},
      {"mallet_uptime_seconds", "gauge"},
      {"mallet_restarts_total", "counter"},
      {"mallet_build_info", "gauge"},
  };
  for (const auto& [name, type] : families) {
    EXPECT_NE(text.find(std::string("# HELP ") + name + " "), std::string::npos) << name;
    EXPECT_TRUE(has_line(text, std::string("# TYPE ") + name + " " + type)) << name << "\n" << text;
  }
  EXPECT_TRUE(has_line(text, "mallet_build_info{version=\"0.1.0\"} 1")) << text;
  // The visitor study's outcomes are there from 0, so that an alert on one can fire.
  for (const char* outcome : {"completed", "abandoned", "declined"})
    EXPECT_TRUE(has_line(text, std::string("mallet_visitor_study_sessions_total{outcome=\"") + outcome + "\"} 0"))
        << text;
  // Unknown gauges are NaN, not missing: a series that comes and goes breaks alerts.
  EXPECT_TRUE(has_line(text, "mallet_remote_battery_ratio NaN")) << text;
  EXPECT_TRUE(has_line(text, "mallet_audio_output_latency_seconds NaN")) << text;
  EXPECT_TRUE(has_line(text, "mallet_vulkan_device_memory_bytes NaN")) << text;
  m.vulkan_device_memory_bytes = 25165824;
  EXPECT_TRUE(has_line(render_prometheus_text(m), "mallet_vulkan_device_memory_bytes 25165824"));
  EXPECT_EQ(text.back(), '\n');
}

TEST(KioskMetrics, OneStateSeriesPerKioskStateAndOnlyTheCurrentOneIsOne) {
  KioskMetrics m;
  m.observe_state(KioskState::operator_page, 5 * kS, 0);
  const std::string text = render_prometheus_text(m);
  EXPECT_TRUE(has_line(text, "mallet_state{state=\"attract\"} 0")) << text;
  EXPECT_TRUE(has_line(text, "mallet_state{state=\"play\"} 0")) << text;
  EXPECT_TRUE(has_line(text, "mallet_state{state=\"calibration\"} 0")) << text;
  EXPECT_TRUE(has_line(text, "mallet_state{state=\"operator\"} 1")) << text;
}

TEST(KioskMetrics, AVisitorSessionRunsFromPlayToTheLastMovementBeforeAttract) {
  KioskMetrics m;
  m.observe_state(KioskState::attract, 0, 0);
  m.observe_state(KioskState::play, 10 * kS, 10 * kS);  // a visitor picks up the mallet
  m.observe_state(KioskState::play, 10 * kS, 50 * kS);
  EXPECT_EQ(m.visitor_sessions(), 1u);
  EXPECT_EQ(m.session_histogram().count(), 0u);  // still playing
  // 45 s without movement: Attract at 95 s; the visitor played 40 s.
  m.observe_state(KioskState::attract, 95 * kS, 50 * kS);
  EXPECT_EQ(m.session_histogram().count(), 1u);
  EXPECT_EQ(m.session_histogram().sum_ns(), 40 * kS);
  // The operator page and a calibration within a session do not start another one.
  m.observe_state(KioskState::play, 100 * kS, 100 * kS);
  m.observe_state(KioskState::operator_page, 101 * kS, 100 * kS);
  m.observe_state(KioskState::play, 103 * kS, 103 * kS);
  m.observe_state(KioskState::attract, 150 * kS, 105 * kS);
  EXPECT_EQ(m.visitor_sessions(), 2u);
  EXPECT_EQ(m.session_histogram().count(), 2u);
  EXPECT_EQ(m.session_histogram().sum_ns(), 45 * kS);
  const std::string text = render_prometheus_text(m);
  EXPECT_TRUE(has_line(text, "mallet_visitor_sessions_total 2")) << text;
  EXPECT_TRUE(has_line(text, "mallet_visitor_session_seconds_bucket{le=\"5\"} 1")) << text;
  EXPECT_TRUE(has_line(text, "mallet_visitor_session_seconds_bucket{le=\"60\"} 2")) << text;
  EXPECT_TRUE(has_line(text, "mallet_visitor_session_seconds_sum 45")) << text;
}

TEST(KioskMetrics, TrackingLostTimeCountsOnlyWhileLost) {
  KioskMetrics m;
  m.observe_tracking(false, 0);
  m.observe_tracking(true, 1 * kS);
  m.observe_tracking(true, 1500 * kMillisecond);
  m.observe_tracking(false, 3 * kS);  // lost from 1 s to 3 s
  m.observe_tracking(false, 10 * kS);
  m.observe_tracking(true, 10 * kS);
  m.observe_tracking(false, 10250 * kMillisecond);
  EXPECT_EQ(m.tracking_lost_ns(), 2250 * kMillisecond);
  EXPECT_TRUE(has_line(render_prometheus_text(m), "mallet_tracking_lost_seconds_total 2.25"));
}

}  // namespace
}  // namespace mallet
