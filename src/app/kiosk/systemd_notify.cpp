#include "app/kiosk/systemd_notify.hpp"

#include <cerrno>
#include <charconv>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <utility>

#include <unistd.h>

namespace mallet::app {

namespace {

std::string env_or_empty(const char* name) {
  const char* value = std::getenv(name);
  return value ? value : "";
}

//! A positive decimal integer, the whole of `text`.
template <typename T>
std::optional<T> parse_positive(std::string_view text) {
  T value{};
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc{} || end != text.data() + text.size() || value <= 0) return std::nullopt;
  return value;
}

//! The parent of `pid` from /proc/PID/stat (its 4th field, after the parenthesised name,
//! which may itself contain spaces and parentheses); 0 if unknown.
long parent_of(long pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::stringstream text;
  text << in.rdbuf();
  const std::string stat = text.str();
  const auto name_end = stat.rfind(')');
  if (name_end == std::string::npos) return 0;
  std::istringstream fields(stat.substr(name_end + 1));
  std::string state;
  long parent = 0;
  fields >> state >> parent;
  return fields ? parent : 0;
}

}  // namespace

NotifyEnvironment NotifyEnvironment::from_process() {
  return {env_or_empty("NOTIFY_SOCKET"), env_or_empty("WATCHDOG_USEC"), env_or_empty("WATCHDOG_PID")};
}

std::string reload_command(const NotifyEnvironment& env, long pid) {
  return env.notify_socket.empty() ? "kill -HUP " + std::to_string(pid) : "systemctl reload mallet";
}

std::optional<Nanos> watchdog_half_period(std::string_view watchdog_usec) {
  const auto usec = parse_positive<Nanos>(watchdog_usec);
  if (!usec || *usec > std::numeric_limits<Nanos>::max() / 1000) return std::nullopt;
  return *usec * 1000 / 2;
}

bool is_self_or_ancestor(long pid) {
  if (pid <= 0) return false;
  long current = static_cast<long>(getpid());
  for (int depth = 0; depth < 4096 && current > 0; ++depth) {  // bounded, whatever /proc says
    if (current == pid) return true;
    current = parent_of(current);
  }
  return false;
}

SystemdNotifier::SystemdNotifier(const NotifyEnvironment& env) {
  if (env.notify_socket.empty()) return;  // not started by systemd (or not Type=notify)

  // The watchdog is ours if systemd watches this process or the chain that started it.
  if (const auto half = watchdog_half_period(env.watchdog_usec)) {
    const auto watched = parse_positive<long>(env.watchdog_pid);
    if (env.watchdog_pid.empty() || (watched && is_self_or_ancestor(*watched))) watchdog_interval_ = half;
  }

  const std::string& name = env.notify_socket;
  if (name.front() != '/' && name.front() != '@') {
    problem_ = "NOTIFY_SOCKET=" + name + ": neither an absolute path nor an abstract name (@...)";
    return;
  }
  if (name.size() >= sizeof address_.sun_path) {
    problem_ = "NOTIFY_SOCKET=" + name + ": longer than a socket address may be";
    return;
  }
  address_.sun_family = AF_UNIX;
  std::memcpy(address_.sun_path, name.data(), name.size());
  // An abstract name starts with a NUL and is exactly as long as given; a path counts its NUL.
  if (name.front() == '@') address_.sun_path[0] = '\0';
  address_length_ = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + name.size() +
                                           (name.front() == '@' ? 0 : 1));

  fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
  if (fd_ < 0) problem_ = std::string("socket(AF_UNIX, SOCK_DGRAM): ") + std::strerror(errno);
}

SystemdNotifier::~SystemdNotifier() { close_socket(); }

SystemdNotifier::SystemdNotifier(SystemdNotifier&& other) noexcept
    : fd_(std::exchange(other.fd_, -1)),
      address_(other.address_),
      address_length_(other.address_length_),
      watchdog_interval_(other.watchdog_interval_),
      problem_(std::move(other.problem_)) {}

SystemdNotifier& SystemdNotifier::operator=(SystemdNotifier&& other) noexcept {
  if (this != &other) {
    close_socket();
    fd_ = std::exchange(other.fd_, -1);
    address_ = other.address_;
    address_length_ = other.address_length_;
    watchdog_interval_ = other.watchdog_interval_;
    problem_ = std::move(other.problem_);
  }
  return *this;
}

void SystemdNotifier::close_socket() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

bool SystemdNotifier::send(std::string_view message) {
  if (fd_ < 0 || message.empty()) return false;
  // Non-blocking: a busy or vanished systemd costs one failed call, never a stalled frame.
  const ssize_t sent = ::sendto(fd_, message.data(), message.size(), MSG_NOSIGNAL | MSG_DONTWAIT,
                                reinterpret_cast<const sockaddr*>(&address_), address_length_);
  return sent == static_cast<ssize_t>(message.size());
}

bool SystemdNotifier::status(std::string_view text) {
  std::string message = "STATUS=";
  message += text;
  for (std::size_t i = 7; i < message.size(); ++i)
    if (message[i] == '\n' || message[i] == '\r') message[i] = ' ';  // one assignment per line
  return send(message);
}

}  // namespace mallet::app
