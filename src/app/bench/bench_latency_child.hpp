#pragma once
// A program `mallet bench latency` starts and owns (Xvfb, jackd, the kiosk under test):
// started with the bench's environment plus its own variables, its output read line by
// line on a thread (each line stamped on the monotonic clock as it arrives), and ended
// when its owner goes, whatever the reason: SIGTERM, a bounded wait, then SIGKILL. The
// child also gets PR_SET_PDEATHSIG, so a bench that is itself killed leaves no orphan,
// and its own process group, so a Ctrl+C in the terminal reaches the bench only (which
// then tears everything down in order).
#include <sys/types.h>

#include <atomic>
#include <chrono>
#include <deque>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <string_view>
#include <thread>
#include <utility>
#include <vector>

#include "core/time.hpp"

namespace mallet::app::latency {

struct ChildOptions {
  std::vector<std::string> argv;                         //!< argv[0] is looked up in PATH
  std::vector<std::pair<std::string, std::string>> env;  //!< set on top of the bench's own
  int keep_fd = -1;                                      //!< a descriptor the child inherits (Xvfb -displayfd)
  //! Each line the child writes on stdout or stderr, on the reader thread, stamped as it arrived.
  std::function<void(Nanos, std::string_view)> on_line;
};

class Child {
 public:
  //! Starts it; throws std::runtime_error naming the program when it cannot be executed.
  explicit Child(ChildOptions options);
  ~Child();
  Child(const Child&) = delete;
  Child& operator=(const Child&) = delete;

  //! SIGTERM, up to `grace` for it to exit, then SIGKILL (and wait). Idempotent.
  void stop(std::chrono::milliseconds grace = std::chrono::milliseconds(2000));
  //! Still running (reaps it when it has exited).
  bool running();
  //! How it ended ("exit 1", "signal 9"), empty while it runs.
  std::string ended_how();
  pid_t pid() const { return pid_; }
  const std::string& name() const { return name_; }
  //! Its last `n` lines of output (for an error message).
  std::string tail(std::size_t n) const;

 private:
  void read_output();
  void reap(int status);

  std::string name_;
  pid_t pid_ = -1;
  int out_fd_ = -1;
  bool reaped_ = false;
  std::string ended_;
  std::function<void(Nanos, std::string_view)> on_line_;
  mutable std::mutex tail_mutex_;
  std::deque<std::string> tail_;
  std::atomic<bool> stop_reading_{false};
  std::thread reader_;
};

}  // namespace mallet::app::latency
