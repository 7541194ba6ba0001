#pragma once
// Tells systemd how the kiosk is doing (sd_notify(3)'s protocol, without libsystemd):
// one datagram of `KEY=VALUE` lines to the AF_UNIX socket named by $NOTIFY_SOCKET
// (a path, or a Linux abstract name when it starts with '@').
//
// mallet.service runs the kiosk as its main process (NotifyAccess=main; its display, cage,
// is another unit: a seat session's processes leave the unit's cgroup, and systemd would
// drop their messages). The watchdog is taken from $WATCHDOG_USEC as long as $WATCHDOG_PID
// is this process or one of its ancestors (a wrapper that execs or forks the kiosk), never
// a stranger's.
//
// Every call is one non-blocking sendto(): it never waits for systemd, never throws, and
// returns whether the message left. Not for the audio callback (status() builds a string).
//
// Why not libsystemd's sd_notify(3): Debian 12's (252) sends on a blocking socket, so a
// queue systemd has not read stops the caller (measured: 5000 WATCHDOG=1 to an unread
// socket hung in sendmsg until killed 3 s later), and sd_watchdog_enabled() answers 0 when
// $WATCHDOG_PID is not the caller (a wrapper's).
#include <optional>
#include <string>
#include <string_view>

#include <sys/socket.h>
#include <sys/un.h>

#include "core/time.hpp"

namespace mallet::app {

//! What systemd put in the environment, as text (empty = not set).
struct NotifyEnvironment {
  std::string notify_socket;  //!< $NOTIFY_SOCKET
  std::string watchdog_usec;  //!< $WATCHDOG_USEC: the unit's WatchdogSec= in microseconds
  std::string watchdog_pid;   //!< $WATCHDOG_PID: the process systemd watches

  static NotifyEnvironment from_process();
};

//! What an operator types to make this kiosk reload its settings: `systemctl reload mallet`
//! when systemd started it (its unit sets $NOTIFY_SOCKET), else a SIGHUP to process `pid`
//! (`kill -HUP PID`: a kiosk started by hand, which no unit reloads).
std::string reload_command(const NotifyEnvironment& env, long pid);

class SystemdNotifier {
 public:
  //! Not under systemd: every message is dropped (and reported as not sent).
  SystemdNotifier() = default;
  explicit SystemdNotifier(const NotifyEnvironment& env);
  static SystemdNotifier from_environment() { return SystemdNotifier(NotifyEnvironment::from_process()); }
  ~SystemdNotifier();
  SystemdNotifier(SystemdNotifier&& other) noexcept;
  SystemdNotifier& operator=(SystemdNotifier&& other) noexcept;
  SystemdNotifier(const SystemdNotifier&) = delete;
  SystemdNotifier& operator=(const SystemdNotifier&) = delete;

  //! Whether $NOTIFY_SOCKET named a socket we can send to.
  bool enabled() const { return fd_ >= 0; }
  //! Why not, when not enabled and $NOTIFY_SOCKET was set (empty otherwise).
  const std::string& problem() const { return problem_; }

  //! READY=1: start-up is over (the unit is Type=notify; `systemctl start` returns now).
  bool ready() { return send("READY=1"); }
  //! WATCHDOG=1: alive. Send every watchdog_interval(), and only while input, audio and
  //! render all are; systemd kills and restarts the kiosk when these stop.
  bool watchdog() { return send("WATCHDOG=1"); }
  //! STOPPING=1: shutting down on purpose (an operator's quit, SIGTERM).
  bool stopping() { return send("STOPPING=1"); }
  //! RELOADING=1: re-reading the configuration (SIGHUP); send ready() when done.
  bool reloading() { return send("RELOADING=1"); }
  //! STATUS=text, shown by `systemctl status mallet` (line breaks become spaces).
  bool status(std::string_view text);
  //! Any message, e.g. "READY=1\nSTATUS=playing". Sent as is.
  bool send(std::string_view message);

  //! How often to send watchdog(): half of $WATCHDOG_USEC, as systemd advises; nothing when
  //! the unit has no watchdog, the value is not a positive integer, or $WATCHDOG_PID names a
  //! process that is neither this one nor an ancestor.
  std::optional<Nanos> watchdog_interval() const { return watchdog_interval_; }

 private:
  void close_socket();

  int fd_ = -1;
  sockaddr_un address_{};
  socklen_t address_length_ = 0;
  std::optional<Nanos> watchdog_interval_;
  std::string problem_;
};

//! Half of a $WATCHDOG_USEC value in nanoseconds; nothing unless it is a positive decimal
//! integer that fits.
std::optional<Nanos> watchdog_half_period(std::string_view watchdog_usec);

//! Whether `pid` is this process or one of its ancestors (read from /proc).
bool is_self_or_ancestor(long pid);

}  // namespace mallet::app
