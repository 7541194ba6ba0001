#include "app/bench/bench_kiosk_child.hpp"

#include <stdlib.h>
#include <time.h>

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "app/common/programs.hpp"

namespace mallet::app::latency {

namespace {
std::atomic<int> g_signal{0};
void on_signal(int s) { g_signal.store(s); }
constexpr int kSignals[3] = {SIGINT, SIGTERM, SIGHUP};
}  // namespace

TempDir::TempDir(const std::string& prefix) {
  std::string pattern = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
  if (!mkdtemp(pattern.data())) throw std::runtime_error("cannot create a temporary folder in " + pattern);
  path_ = pattern;
}

TempDir::~TempDir() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

KioskFolders::KioskFolders(const std::string& prefix)
    : temp(prefix),
      runtime(temp.path() / "runtime"),
      state(temp.path() / "state"),
      metrics(temp.path() / "kiosk.prom"),
      settings(temp.path() / "settings.toml") {
  std::filesystem::create_directories(runtime);
  std::filesystem::create_directories(state);
  std::filesystem::permissions(runtime, std::filesystem::perms::owner_all);
}

std::vector<std::pair<std::string, std::string>> KioskFolders::kiosk_env(const std::string& display,
                                                                         const std::string& jack_server) const {
  std::vector<std::pair<std::string, std::string>> env = {{"DISPLAY", display},
                                                          {"JACK_DEFAULT_SERVER", jack_server},
                                                          {"JACK_NO_START_SERVER", "1"},
                                                          {"XDG_RUNTIME_DIR", runtime.string()},
                                                          {"MALLET_STATE_DIR", state.string()}};
  if (const std::optional<std::string> preload = child_preload()) env.emplace_back("LD_PRELOAD", *preload);
  return env;
}

std::string read_all(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

void require_x_and_jack(const std::string& bench) {
  for (const auto& [program, package] : {std::pair<const char*, const char*>{"Xvfb", "xvfb"}, {"jackd", "jackd2"}})
    if (find_program(program).empty())
      throw std::runtime_error(bench + " needs " + program + ": install the Debian package " + package);
}

std::filesystem::path kiosk_executable(const std::string& bench) {
  const std::filesystem::path kiosk = sibling_program("mallet");
  if (kiosk.empty())
    throw std::runtime_error(bench + ": cannot find the kiosk, mallet: it is neither beside this program nor on PATH "
                             "(install the Debian package mallet)");
  return kiosk;
}

void write_text(const std::filesystem::path& p, const std::string& text) {
  std::ofstream out(p);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + p.string());
}

std::optional<std::string> child_preload() {
  const char* preload = std::getenv("LD_PRELOAD");
  if (!preload) return std::nullopt;
  std::string kept, entry;
  std::stringstream in(preload);
  while (std::getline(in, entry, ':'))
    if (!entry.empty() && entry.find("VkLayer") == std::string::npos) kept += (kept.empty() ? "" : ":") + entry;
  return kept;
}

std::optional<Nanos> parse_log_seconds(std::string_view s) {
  const bool negative = !s.empty() && s[0] == '-';
  if (negative) s.remove_prefix(1);
  Nanos whole = 0, frac = 0;
  std::size_t i = 0;
  for (; i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])); ++i) whole = whole * 10 + (s[i] - '0');
  if (i == 0 || i >= s.size() || s[i] != '.') return std::nullopt;
  int digits = 0;
  for (++i; i < s.size() && std::isdigit(static_cast<unsigned char>(s[i])) && digits < 9; ++i, ++digits)
    frac = frac * 10 + (s[i] - '0');
  for (; digits < 9; ++digits) frac *= 10;
  const Nanos t = whole * kNanosPerSecond + frac;
  return negative ? -t : t;
}

StopSignals::StopSignals() {
  g_signal.store(0);
  struct sigaction sa {};
  sa.sa_handler = on_signal;
  sigemptyset(&sa.sa_mask);
  for (std::size_t i = 0; i < 3; ++i) sigaction(kSignals[i], &sa, &old_[i]);
}

StopSignals::~StopSignals() {
  for (std::size_t i = 0; i < 3; ++i) sigaction(kSignals[i], &old_[i], nullptr);
}

int stop_signal() { return g_signal.load(); }

void sleep_until(Nanos t) {
  timespec ts{static_cast<time_t>(t / kNanosPerSecond), static_cast<long>(t % kNanosPerSecond)};
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
    if (g_signal.load()) return;
  }
}

void kiosk_failed(Child& kiosk, const std::string& bench, const std::string& what) {
  throw std::runtime_error(bench + ": the kiosk " + what + " (" +
                           (kiosk.running() ? std::string("still running") : kiosk.ended_how()) +
                           "); its last lines:\n" + kiosk.tail(15));
}

void wait_for_kiosk(Child& kiosk, const std::string& bench, const std::string& what, Nanos within,
                    const std::function<bool()>& done, const std::function<void()>& check) {
  const Nanos until = monotonic_now() + within;
  while (!done()) {
    check();
    if (!kiosk.running()) kiosk_failed(kiosk, bench, "exited before " + what);
    if (monotonic_now() > until)
      kiosk_failed(kiosk, bench,
                   "did not get to " + what + " within " + std::to_string(within / kNanosPerSecond) + " s");
    sleep_ms(20);
  }
}

void sleep_ms(double ms) { sleep_until(monotonic_now() + static_cast<Nanos>(ms * 1e6)); }

}  // namespace mallet::app::latency
