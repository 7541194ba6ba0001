// `mallet bench soak`'s figures: what it reads from /proc and from the kiosk's metrics file,
// the p99 of a minute's frames, the growth per hour and the CSV and plot it writes.
#include "app/bench/bench_soak_figures.hpp"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <thread>

#include <gtest/gtest.h>

#include "core/kiosk_metrics.hpp"

namespace mallet::app::soak {
namespace {

TEST(SoakFigures, ReadsThisProcessAndSeesADescriptorAndAThreadMore) {
  const std::optional<ProcessSample> a = read_process(getpid());
  ASSERT_TRUE(a);
  EXPECT_GT(a->rss_bytes, 1u << 20);
  EXPECT_GE(a->threads, 1);
  const int fd = open("/dev/null", O_RDONLY);
  ASSERT_GE(fd, 0);
  std::optional<ProcessSample> b;
  std::thread t([&] { b = read_process(getpid()); });
  t.join();
  close(fd);
  ASSERT_TRUE(b);
  EXPECT_EQ(b->fds, a->fds + 1);
  EXPECT_EQ(b->threads, a->threads + 1);
}

TEST(SoakFigures, ReadsTheCpuTimeAProcessHasUsedWhichGrowsWithItsWork) {
  const std::optional<ProcessSample> a = read_process(getpid());
  ASSERT_TRUE(a);
  // Work until the kernel has counted at least one more tick (10 ms at 100 Hz) of this
  // process's CPU; a process that read 0 or a value that never moved would never get there.
  volatile double sink = 0;
  std::optional<ProcessSample> b = a;
  for (int round = 0; round < 2000 && b && b->cpu_ns <= a->cpu_ns; ++round) {
    for (int i = 0; i < 1'000'000; ++i) sink = sink + std::sqrt(static_cast<double>(i));
    b = read_process(getpid());
  }
  ASSERT_TRUE(b);
  EXPECT_GT(a->cpu_ns, 0);
  EXPECT_GT(b->cpu_ns, a->cpu_ns);
  EXPECT_EQ((b->cpu_ns - a->cpu_ns) % (1'000'000'000 / sysconf(_SC_CLK_TCK)), 0);  // whole ticks
}

TEST(SoakFigures, AProcessThatIsGoneIsNothing) {
  const pid_t child = fork();
  if (child == 0) _exit(0);
  int status = 0;
  waitpid(child, &status, 0);
  EXPECT_FALSE(read_process(child));
}

TEST(SoakFigures, ReadsBackWhatTheKioskWrites) {
  KioskMetrics m;
  m.version = "1";
  m.strikes[{"xylophone", "wood"}] = 7;
  m.strikes[{"glockenspiel", "metal"}] = 5;
  m.vulkan_device_memory_bytes = 6881280;
  for (int i = 0; i < 90; ++i) m.count_frame(3'000'000);
  for (int i = 0; i < 10; ++i) m.count_frame(30'000'000);
  const std::optional<KioskFigures> f = parse_kiosk_figures(render_prometheus_text(m));
  ASSERT_TRUE(f);
  EXPECT_EQ(f->strikes, 12u);
  EXPECT_EQ(f->frames, 100u);
  EXPECT_EQ(f->vulkan_bytes, 6881280.0);
  ASSERT_EQ(f->frame_seconds.size(), frame_seconds_buckets().size() + 1);
  EXPECT_TRUE(std::isinf(f->frame_seconds.back().first));
  EXPECT_EQ(f->frame_seconds.back().second, 100u);
  EXPECT_EQ(f->frame_seconds[1], (std::pair<double, std::uint64_t>{0.004, 90}));
}

TEST(SoakFigures, ATextWithoutTheFramesIsRefused) {
  EXPECT_FALSE(parse_kiosk_figures("mallet_strikes_total 3\nmallet_vulkan_device_memory_bytes 1\n"));
  EXPECT_FALSE(parse_kiosk_figures(""));
}

TEST(SoakFigures, TheQuantileOfAMinuteIsTheDifferenceOfTwoReadings) {
  const double inf = std::numeric_limits<double>::infinity();
  const Buckets before{{0.01, 100}, {0.02, 100}, {inf, 100}};
  // This minute: 90 frames ≤ 10 ms, 10 in (10, 20] ms.
  const Buckets now{{0.01, 190}, {0.02, 200}, {inf, 200}};
  EXPECT_NEAR(histogram_quantile(0.5, now, before), 0.01 * 50 / 90, 1e-12);
  EXPECT_NEAR(histogram_quantile(0.99, now, before), 0.01 + 0.01 * 9 / 10, 1e-12);
  // Past the last finite bound: that bound, as Prometheus says.
  const Buckets slow{{0.01, 100}, {0.02, 100}, {inf, 150}};
  EXPECT_EQ(histogram_quantile(0.99, slow, before), 0.02);
  EXPECT_TRUE(std::isnan(histogram_quantile(0.99, before, before)));
}

TEST(SoakFigures, GrowthIsTheLeastSquaresSlopePerHour) {
  EXPECT_DOUBLE_EQ(slope({0, 1, 2, 3}, {5, 7, 9, 11}), 2.0);
  EXPECT_DOUBLE_EQ(slope({0, 1, 2, 3}, {1, -1, 1, -1}), -0.4);
  EXPECT_EQ(slope({1}, {3}), 0.0);
  std::vector<Minute> rows;
  for (int i = 0; i <= 120; ++i) {
    Minute m;
    m.hours = i / 60.0;
    m.rss_mib = 100 + 0.5 * m.hours + (i % 2 ? 0.25 : -0.25);  // half a MiB an hour under noise
    m.fds = 23;
    m.threads = 11;
    rows.push_back(m);
  }
  const std::vector<Growth> g = growth_per_hour(rows);
  ASSERT_EQ(g.front().column, "rss_mib");
  EXPECT_NEAR(g.front().per_hour, 0.5, 0.01);
  EXPECT_EQ(g[1].column, "fds");
  EXPECT_EQ(g[1].per_hour, 0.0);
}

TEST(SoakFigures, ARowHasAValueForEachColumnOfTheHeader) {
  Minute m;
  m.hours = 1.5;
  m.rss_mib = 81.25;
  m.strikes = 40;
  m.lost = 1;
  m.state = "play";
  const auto columns = [](const std::string& line) { return std::count(line.begin(), line.end(), ',') + 1; };
  EXPECT_EQ(columns(csv_row(m)), columns(csv_header()));
  EXPECT_EQ(csv_header().substr(0, 14), "hours,rss_mib,");
  EXPECT_EQ(csv_row(m).substr(0, 13), "1.5000,81.25,");
  m.xruns = 3;
  EXPECT_EQ(csv_row(m).substr(csv_row(m).size() - 7), ",play,3");
}

TEST(SoakFigures, ThePlotHasAPanelPerFigureWithItsGrowth) {
  std::vector<Minute> rows(3);
  for (int i = 0; i < 3; ++i) rows[static_cast<std::size_t>(i)].hours = i, rows[static_cast<std::size_t>(i)].fds = 20 + i;
  const std::string svg = svg_plot(rows);
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  std::size_t panels = 0;
  for (std::size_t at = 0; (at = svg.find("<polyline", at)) != std::string::npos; ++at) ++panels;
  EXPECT_EQ(panels, growth_per_hour(rows).size());
  EXPECT_NE(svg.find("fds: +1 descriptors per hour"), std::string::npos) << svg;
}

}  // namespace
}  // namespace mallet::app::soak
