// The kiosk's messages to systemd (sd_notify's protocol) arrive on a real AF_UNIX datagram
// socket, bound here in a scratch directory or in the abstract namespace as systemd does.
#include <array>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <string>

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include "app/kiosk/systemd_notify.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

//! systemd's end: a bound datagram socket; `name` as $NOTIFY_SOCKET spells it.
class Receiver {
 public:
  explicit Receiver(const std::string& name) {
    fd_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC | SOCK_NONBLOCK, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::memcpy(address.sun_path, name.data(), name.size());
    socklen_t length = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + name.size());
    if (name[0] == '@') {
      address.sun_path[0] = '\0';
    } else {
      length += 1;
    }
    bound_ = fd_ >= 0 && ::bind(fd_, reinterpret_cast<const sockaddr*>(&address), length) == 0;
  }
  ~Receiver() {
    if (fd_ >= 0) ::close(fd_);
  }
  Receiver(const Receiver&) = delete;
  Receiver& operator=(const Receiver&) = delete;

  bool bound() const { return bound_; }
  //! The next datagram, or "(none)" if nothing is waiting (the sender never blocks us).
  std::string next() {
    std::array<char, 4096> buffer{};
    const ssize_t n = ::recv(fd_, buffer.data(), buffer.size(), 0);
    return n < 0 ? std::string("(none)") : std::string(buffer.data(), static_cast<std::size_t>(n));
  }

 private:
  int fd_ = -1;
  bool bound_ = false;
};

NotifyEnvironment at(const std::string& socket, const std::string& usec = "", const std::string& pid = "") {
  return {socket, usec, pid};
}

TEST(SystemdNotify, WithoutNotifySocketNothingIsSentAndThereIsNoWatchdog) {
  SystemdNotifier notifier(at("", "10000000"));
  EXPECT_FALSE(notifier.enabled());
  EXPECT_TRUE(notifier.problem().empty());
  EXPECT_FALSE(notifier.ready());
  EXPECT_FALSE(notifier.watchdog());
  EXPECT_FALSE(notifier.status("playing"));
  EXPECT_EQ(notifier.watchdog_interval(), std::nullopt);
  EXPECT_FALSE(SystemdNotifier().enabled());
}

TEST(SystemdNotify, ReadyWatchdogStatusAndStoppingArriveAsDatagramsOnAPathSocket) {
  const std::string path = (test::scratch_dir() / "notify.sock").string();
  Receiver systemd(path);
  ASSERT_TRUE(systemd.bound()) << path << ": " << std::strerror(errno);

  SystemdNotifier notifier(at(path));
  ASSERT_TRUE(notifier.enabled()) << notifier.problem();
  EXPECT_TRUE(notifier.ready());
  EXPECT_TRUE(notifier.watchdog());
  EXPECT_TRUE(notifier.status("remote lost\nattract mode"));
  EXPECT_TRUE(notifier.reloading());
  EXPECT_TRUE(notifier.stopping());
  EXPECT_EQ(systemd.next(), "READY=1");
  EXPECT_EQ(systemd.next(), "WATCHDOG=1");
  EXPECT_EQ(systemd.next(), "STATUS=remote lost attract mode") << "a line break would start another assignment";
  EXPECT_EQ(systemd.next(), "RELOADING=1");
  EXPECT_EQ(systemd.next(), "STOPPING=1");
  EXPECT_EQ(systemd.next(), "(none)");

  // Moved, it still sends; the moved-from one is inert.
  SystemdNotifier moved = std::move(notifier);
  EXPECT_TRUE(moved.send("READY=1\nSTATUS=up"));
  EXPECT_EQ(systemd.next(), "READY=1\nSTATUS=up");
}

TEST(SystemdNotify, AnAtSignNamesASocketInTheAbstractNamespace) {
  const std::string name = "@mallet-notify-test-" + std::to_string(getpid());
  Receiver systemd(name);
  ASSERT_TRUE(systemd.bound()) << name << ": " << std::strerror(errno);
  SystemdNotifier notifier(at(name));
  ASSERT_TRUE(notifier.enabled());
  EXPECT_TRUE(notifier.watchdog());
  EXPECT_EQ(systemd.next(), "WATCHDOG=1");

  // A path spelt like the name is a different socket: nothing arrives from it.
  SystemdNotifier elsewhere(at("/" + name.substr(1)));
  EXPECT_FALSE(elsewhere.watchdog());
  EXPECT_EQ(systemd.next(), "(none)");
}

TEST(SystemdNotify, AGoneOrMalformedSocketIsReportedNeverThrown) {
  const auto dir = test::scratch_dir();
  SystemdNotifier gone(at((dir / "nobody-listens.sock").string()));
  EXPECT_TRUE(gone.enabled());
  EXPECT_FALSE(gone.ready());  // ENOENT: false, and the kiosk goes on

  SystemdNotifier relative(at("run/notify"));
  EXPECT_FALSE(relative.enabled());
  EXPECT_NE(relative.problem().find("NOTIFY_SOCKET=run/notify"), std::string::npos) << relative.problem();
  EXPECT_FALSE(relative.ready());

  SystemdNotifier too_long(at("/" + std::string(200, 'x')));
  EXPECT_FALSE(too_long.enabled());
  EXPECT_NE(too_long.problem().find("longer"), std::string::npos) << too_long.problem();
}

TEST(SystemdNotify, AFullQueueFailsTheSendInsteadOfBlockingTheKiosk) {
  const std::string path = (test::scratch_dir() / "notify.sock").string();
  Receiver systemd(path);  // never read until the end: its queue fills
  ASSERT_TRUE(systemd.bound());
  SystemdNotifier notifier(at(path));
  int refused = 0;
  for (int i = 0; i < 100'000 && refused == 0; ++i) refused += !notifier.watchdog();
  EXPECT_GT(refused, 0) << "a blocking socket would have hung here instead";
  EXPECT_EQ(systemd.next(), "WATCHDOG=1");
}

TEST(SystemdNotify, TheWatchdogIntervalIsHalfOfWatchdogUsec) {
  EXPECT_EQ(watchdog_half_period("10000000"), 5 * kNanosPerSecond);  // WatchdogSec=10
  EXPECT_EQ(watchdog_half_period("1"), 500);
  for (const char* bad : {"", "0", "-10", "10s", " 10", "1e6", "abc", "99999999999999999999"})
    EXPECT_EQ(watchdog_half_period(bad), std::nullopt) << '"' << bad << '"';
  EXPECT_EQ(watchdog_half_period("9223372036854775"), 4611686018427387500) << "the largest that fits";
  EXPECT_EQ(watchdog_half_period("9223372036854776"), std::nullopt) << "overflows as nanoseconds";

  SystemdNotifier notifier(at("/run/systemd/notify", "10000000"));
  EXPECT_EQ(notifier.watchdog_interval(), 5 * kNanosPerSecond);
  EXPECT_EQ(SystemdNotifier(at("/run/systemd/notify")).watchdog_interval(), std::nullopt) << "no WatchdogSec=";
}

TEST(SystemdNotify, UnderCageTheWatchedPidIsAnAncestorAndStillCounts) {
  const std::string socket = "/run/systemd/notify";
  const std::string usec = "4000000";
  // systemd names the process it started: the unit's wrapper, cage's parent, our ancestor.
  EXPECT_EQ(SystemdNotifier(at(socket, usec, std::to_string(getpid()))).watchdog_interval(), 2 * kNanosPerSecond);
  EXPECT_EQ(SystemdNotifier(at(socket, usec, std::to_string(getppid()))).watchdog_interval(), 2 * kNanosPerSecond);
  EXPECT_TRUE(is_self_or_ancestor(getppid()));

  // A process that is not in our chain (a child of ours) watches someone else's watchdog.
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    pause();
    _exit(0);
  }
  EXPECT_FALSE(is_self_or_ancestor(child));
  EXPECT_EQ(SystemdNotifier(at(socket, usec, std::to_string(child))).watchdog_interval(), std::nullopt);
  kill(child, SIGKILL);
  waitpid(child, nullptr, 0);

  for (const char* bad : {"0", "-1", "x", "12x"})
    EXPECT_EQ(SystemdNotifier(at(socket, usec, bad)).watchdog_interval(), std::nullopt) << bad;
}

TEST(ReloadCommand, SystemctlOnlyForAKioskSystemdStartedAndASighupForOneStartedByHand) {
  // A kiosk started by hand was told "systemctl reload mallet", which reloads another one or
  // none (issue 48, item 13): it is told the signal its own process takes.
  NotifyEnvironment unit;
  unit.notify_socket = "/run/systemd/notify";
  EXPECT_EQ(reload_command(unit, 4242), "systemctl reload mallet");
  EXPECT_EQ(reload_command(NotifyEnvironment{}, 4242), "kill -HUP 4242");
}

}  // namespace
}  // namespace mallet::app
