#include "app/bench/bench_latency_child.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <stdexcept>

#include "app/common/programs.hpp"

extern char** environ;

namespace mallet::app::latency {

Child::Child(ChildOptions options) : on_line_(std::move(options.on_line)) {
  if (options.argv.empty()) throw std::runtime_error("bench latency: nothing to start");
  name_ = options.argv[0];
  const std::string path = find_program(options.argv[0]);
  if (path.empty()) throw std::runtime_error(name_ + " is not installed (not in PATH)");

  // Everything the child needs is built before fork: after it only async-signal-safe calls.
  std::vector<std::string> env_text;
  for (char** e = environ; *e; ++e) {
    const std::string entry = *e;
    bool replaced = false;
    for (const auto& [k, v] : options.env) replaced = replaced || entry.rfind(k + "=", 0) == 0;
    if (!replaced) env_text.push_back(entry);
  }
  for (const auto& [k, v] : options.env) env_text.push_back(k + "=" + v);
  std::vector<char*> envp, argv;
  for (std::string& s : env_text) envp.push_back(s.data());
  envp.push_back(nullptr);
  for (std::string& s : options.argv) argv.push_back(s.data());
  argv.push_back(nullptr);

  int out[2], failed[2];
  if (pipe2(out, O_CLOEXEC) != 0 || pipe2(failed, O_CLOEXEC) != 0)
    throw std::runtime_error("bench latency: pipe: " + std::string(std::strerror(errno)));
  const pid_t parent = getpid();
  pid_ = fork();
  if (pid_ < 0) {
    const int e = errno;
    close(out[0]), close(out[1]), close(failed[0]), close(failed[1]);
    throw std::runtime_error("bench latency: fork: " + std::string(std::strerror(e)));
  }
  if (pid_ == 0) {
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (getppid() != parent) _exit(127);  // the bench died between fork and prctl
    setpgid(0, 0);
    sigset_t none;
    sigemptyset(&none);
    sigprocmask(SIG_SETMASK, &none, nullptr);
    const int devnull = open("/dev/null", O_RDONLY);
    if (devnull >= 0) dup2(devnull, 0);
    dup2(out[1], 1);
    dup2(out[1], 2);
    if (options.keep_fd >= 0) fcntl(options.keep_fd, F_SETFD, 0);  // survives exec
    execve(path.c_str(), argv.data(), envp.data());
    const int e = errno;
    ssize_t ignored = write(failed[1], &e, sizeof e);
    (void)ignored;
    _exit(127);
  }
  close(out[1]);
  close(failed[1]);
  int e = 0;
  ssize_t n;
  do n = read(failed[0], &e, sizeof e);
  while (n < 0 && errno == EINTR);
  close(failed[0]);
  if (n == static_cast<ssize_t>(sizeof e)) {
    close(out[0]);
    int status = 0;
    waitpid(pid_, &status, 0);
    reaped_ = true;
    throw std::runtime_error("cannot run " + path + ": " + std::strerror(e));
  }
  out_fd_ = out[0];
  reader_ = std::thread([this] { read_output(); });
}

Child::~Child() {
  stop();
  stop_reading_.store(true);
  if (reader_.joinable()) reader_.join();
  if (out_fd_ >= 0) close(out_fd_);
}

void Child::read_output() {
  std::string pending;
  char buf[4096];
  for (;;) {
    pollfd p{out_fd_, POLLIN, 0};
    const int r = poll(&p, 1, 100);
    if (r < 0 && errno != EINTR) break;
    if (r <= 0) {
      if (stop_reading_.load()) break;  // bounded: a grandchild holding the pipe cannot keep us here
      continue;
    }
    const ssize_t n = read(out_fd_, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;  // EOF: the child is gone
    const Nanos now = monotonic_now();
    pending.append(buf, static_cast<std::size_t>(n));
    std::size_t nl;
    while ((nl = pending.find('\n')) != std::string::npos) {
      const std::string line = pending.substr(0, nl);
      pending.erase(0, nl + 1);
      if (on_line_) on_line_(now, line);
      std::lock_guard lock(tail_mutex_);
      tail_.push_back(line);
      if (tail_.size() > 60) tail_.pop_front();
    }
  }
}

void Child::reap(int status) {
  reaped_ = true;
  if (WIFEXITED(status))
    ended_ = "exit " + std::to_string(WEXITSTATUS(status));
  else if (WIFSIGNALED(status))
    ended_ = "signal " + std::to_string(WTERMSIG(status));
  else
    ended_ = "ended";
}

bool Child::running() {
  if (reaped_ || pid_ <= 0) return false;
  int status = 0;
  const pid_t r = waitpid(pid_, &status, WNOHANG);
  if (r == pid_) reap(status);
  return !reaped_;
}

std::string Child::ended_how() {
  running();
  return ended_;
}

void Child::stop(std::chrono::milliseconds grace) {
  if (!running()) return;
  kill(pid_, SIGTERM);
  const Nanos deadline = monotonic_now() + std::chrono::duration_cast<std::chrono::nanoseconds>(grace).count();
  while (running() && monotonic_now() < deadline) usleep(10'000);
  if (running()) {
    kill(pid_, SIGKILL);
    int status = 0;
    if (waitpid(pid_, &status, 0) == pid_) reap(status);
  }
}

std::string Child::tail(std::size_t n) const {
  std::lock_guard lock(tail_mutex_);
  std::string text;
  const std::size_t from = tail_.size() > n ? tail_.size() - n : 0;
  for (std::size_t i = from; i < tail_.size(); ++i) text += "    " + tail_[i] + "\n";
  return text;
}

}  // namespace mallet::app::latency
