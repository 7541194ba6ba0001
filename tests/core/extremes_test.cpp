// Numerical stability at the extremes: undamped, very damped, near and above Nyquist,
// 30 days of uptime, no NaN, no subnormal output.
#include <cfloat>
#include <cmath>
#include <limits>

#include <gtest/gtest.h>

#include "core/actuator_signal.hpp"
#include "core/soft_clip.hpp"
#include "core/vibration.hpp"

namespace mallet {
namespace {

constexpr Nanos kOneDay = 86'400 * kNanosPerSecond;

bool finite_and_normal_or_zero(double x) { return std::isfinite(x) && (x == 0.0 || std::fabs(x) >= DBL_MIN); }

TEST(Extremes, UndampedStaysBoundedAndExactAfterTenMinutes) {
  const VibrationParams p{1.0, 0.0, 300.0};
  for (Nanos t = 600 * kNanosPerSecond; t < 600 * kNanosPerSecond + 10'000'000; t += 20'833) {
    const double q = decaying_sine_unit(p, t);
    ASSERT_LE(std::fabs(q), 1.0);
    // Exact phase: 300·t cycles, reduced with integers (t in ns, f integral).
    const long double cycles = static_cast<long double>((t * 300) % kNanosPerSecond) / 1e9L;
    ASSERT_NEAR(q, static_cast<double>(std::sin(2.0L * 3.14159265358979323846L * cycles)), 1e-9) << t;
  }
}

TEST(Extremes, HeavyDecayGoesToExactZeroNotSubnormal) {
  const VibrationParams p{2.0, 1e4, 300.0};
  for (Nanos t = 0; t < 2 * kNanosPerSecond; t += 97'003) {
    const double q = eq1(p, 100.0, t);
    ASSERT_TRUE(finite_and_normal_or_zero(q)) << t << " " << q;
  }
  EXPECT_EQ(eq1(p, 1.0, 100'000'000), 0.0);  // B·t = 1000 > cutoff
}

TEST(Extremes, ThirtyDaysOfUptimeGiveTheSameSignalAsOneSecond) {
  // Eq. 1 sees only the time since the impact; the impact time itself can be huge.
  const VibrationParams metal{0.020, 9.0, 15.0};
  for (Nanos boot : {Nanos{kNanosPerSecond}, 30 * kOneDay, 30 * kOneDay + 123'456'789}) {
    for (Nanos since : {Nanos{0}, Nanos{1}, Nanos{16'666'667}, Nanos{250'000'000}}) {
      const Nanos now = boot + since;
      EXPECT_EQ(eq1(metal, 1.3, now - boot), eq1(metal, 1.3, since));
    }
  }
}

TEST(Extremes, ZeroSpeedIsSilentAndHundredMetresPerSecondIsFinite) {
  const VibrationParams wood{1.0, 80.0, 100.0};
  for (Nanos t = 0; t < kNanosPerSecond; t += 1'000'003) {
    EXPECT_EQ(eq1(wood, 0.0, t), 0.0);
    EXPECT_TRUE(std::isfinite(eq1(wood, 100.0, t)));
  }
}

TEST(Extremes, FrequencyAtOrAboveNyquistIsRefusedWithAReason) {
  Material m;
  m.name = "metal";
  m.actuator = {2.0, 90.0, 300.0};
  EXPECT_FALSE(actuator_band_problem(m, 48000).has_value());
  EXPECT_FALSE(actuator_band_problem(m, 601).has_value());  // 300 < 300.5
  const auto at = actuator_band_problem(m, 600);
  ASSERT_TRUE(at.has_value());
  EXPECT_NE(at->find("Nyquist"), std::string::npos);
  EXPECT_NE(at->find("metal"), std::string::npos);
  EXPECT_TRUE(actuator_band_problem(m, 400).has_value());
}

TEST(Extremes, JustBelowNyquistStillMatchesTheEquationSampleBySample) {
  const int fs = 8000;
  const VibrationParams p{1.0, 50.0, 3999.0};
  Impact impact;
  impact.t_ns = 1'000'000'017;  // between two samples
  impact.speed_m_per_s = 1.0;
  const ActuatorSignal s(impact, p, 1.0, fs);
  for (std::int64_t n = s.start.index; n < s.start.index + 200; ++n) {
    const long double t = static_cast<long double>(n) / fs - 1.000000017L;
    const long double want = std::exp(-50.0L * t) * std::sin(2.0L * 3.14159265358979323846L * 3999.0L * t);
    ASSERT_NEAR(s.at_sample(n, fs), static_cast<double>(want), 1e-9) << n;
  }
}

TEST(Extremes, NonFiniteTimeNeverReachesTheOutput) {
  const VibrationParams p{1.0, 80.0, 100.0};
  EXPECT_EQ(decaying_sine_unit_seconds(p, std::numeric_limits<double>::quiet_NaN()), 0.0);
  EXPECT_EQ(decaying_sine_unit_seconds(p, -1.0), 0.0);
  EXPECT_EQ(decaying_sine_unit_seconds(p, std::numeric_limits<double>::infinity()), 0.0);
}

TEST(SoftClip, IdentityBelowKneeAndNeverBeyondFullScale) {
  EXPECT_EQ(soft_clip(0.5, 0.9), 0.5);
  EXPECT_EQ(soft_clip(-0.9, 0.9), -0.9);
  double previous = 0.9;
  for (double x = 0.9001; x < 1000; x *= 1.1) {
    const double y = soft_clip(x, 0.9);
    ASSERT_LE(y, 1.0);
    ASSERT_GE(y, previous);  // monotonic
    ASSERT_EQ(soft_clip(-x, 0.9), -y);
    previous = y;
  }
  EXPECT_NEAR((soft_clip(0.9 + 1e-7, 0.9) - 0.9) / 1e-7, 1.0, 1e-6);  // slope 1 at the knee
}

}  // namespace
}  // namespace mallet
