#pragma once
// What a bench that runs the real kiosk as a child process needs besides the child itself
// (bench_latency_child.hpp): a private folder for the run, its settings file written, the
// child's LD_PRELOAD made safe, the kiosk's log times read back exactly, and waits that a
// Ctrl+C (SIGINT, SIGTERM, SIGHUP) cuts short so that the bench tears everything down in
// order. Used by `mallet bench latency` and `mallet bench soak`.
#include <atomic>
#include <csignal>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "app/bench/bench_latency_child.hpp"
#include "core/time.hpp"

namespace mallet::app::latency {

//! A private folder `<temp>/<prefix>-XXXXXX`, removed with everything in it afterwards.
class TempDir {
 public:
  explicit TempDir(const std::string& prefix);
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

//! The kiosk under test's own folders in a TempDir (which the bench may use for its own
//! files too): its XDG_RUNTIME_DIR (mode 700), its state folder, and where its settings file
//! and its metrics file go.
struct KioskFolders {
  explicit KioskFolders(const std::string& prefix);
  //! The kiosk's environment: the bench's X server and JACK server, these folders, and
  //! LD_PRELOAD made safe (child_preload).
  std::vector<std::pair<std::string, std::string>> kiosk_env(const std::string& display,
                                                             const std::string& jack_server) const;
  TempDir temp;
  std::filesystem::path runtime, state, metrics, settings;
};

//! Writes `text` to `p`; throws naming the file when it cannot.
void write_text(const std::filesystem::path& p, const std::string& text);
//! All of a file ("" when it cannot be read: a metrics file not written yet).
std::string read_all(const std::filesystem::path& p);

//! Throws "BENCH needs PROGRAM: install the Debian package PACKAGE" unless Xvfb and jackd
//! are installed: every bench that runs the real kiosk starts its own servers.
void require_x_and_jack(const std::string& bench);
//! The kiosk under test's program: `mallet` beside this one (mallet-bench), else on PATH.
//! Throws "BENCH: cannot find the kiosk, mallet: …" when there is none.
std::filesystem::path kiosk_executable(const std::string& bench);

//! LD_PRELOAD without the Vulkan validation layer (the sanitizer tests preload it; GLFW
//! looks vkGetInstanceProcAddr up by name and a preloaded layer would answer). Nothing
//! when the bench has no LD_PRELOAD.
std::optional<std::string> child_preload();

//! A time as the kiosk logs it, "123.456789012" seconds (format_seconds), → ns exactly.
std::optional<Nanos> parse_log_seconds(std::string_view s);

//! While it lives, SIGINT/SIGTERM/SIGHUP only set a flag (stop_signal) that the waits below
//! and the benches' loops look at; the old handlers come back afterwards.
class StopSignals {
 public:
  StopSignals();
  ~StopSignals();
  StopSignals(const StopSignals&) = delete;
  StopSignals& operator=(const StopSignals&) = delete;

 private:
  struct sigaction old_[3]{};
};
//! The signal that asked the bench to stop, 0 when none did.
int stop_signal();

//! Throws "BENCH: the kiosk WHAT (how it ended); its last lines: …".
[[noreturn]] void kiosk_failed(Child& kiosk, const std::string& bench, const std::string& what);

//! Polls `done` every 20 ms until it holds; `check` runs before each poll (a signal, the
//! bench's bound; it throws to stop). Fails (kiosk_failed) when the kiosk exits first
//! ("exited before WHAT") or `within` passes ("did not get to WHAT within N s").
void wait_for_kiosk(Child& kiosk, const std::string& bench, const std::string& what, Nanos within,
                    const std::function<bool()>& done, const std::function<void()>& check);

//! Sleeps until `t` (CLOCK_MONOTONIC) or until a stop signal arrives.
void sleep_until(Nanos t);
void sleep_ms(double ms);

}  // namespace mallet::app::latency
