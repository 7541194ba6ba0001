#include "core/atomic_file.hpp"

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <string>

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

namespace mallet {

namespace {

//! Removes the temporary files of `path` left by processes that no longer run (a SIGKILL or
//! a power cut between creating one and renaming it): ".NAME.tmp-PID-N" with PID gone.
void remove_stale_temporaries(const std::filesystem::path& dir, const std::string& name) {
  const std::string prefix = "." + name + ".tmp-";
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string file = it->path().filename().string();
    if (file.rfind(prefix, 0) != 0) continue;
    const std::string rest = file.substr(prefix.size());
    const std::size_t dash = rest.find('-');
    if (dash == 0 || dash == std::string::npos || rest.find_first_not_of("0123456789-") != std::string::npos) continue;
    const pid_t pid = static_cast<pid_t>(std::stol(rest.substr(0, dash)));
    if (pid != ::getpid() && ::kill(pid, 0) != 0 && errno == ESRCH) {
      std::error_code ignored;
      std::filesystem::remove(it->path(), ignored);
    }
  }
}

}  // namespace

void write_file_atomically(const std::filesystem::path& path, std::string_view bytes) {
  const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  // Unique per process and call, in the same folder so that rename() is atomic.
  static std::atomic<unsigned> counter{0};
  std::string tmp_name = ".";  // built by appends: GCC 12 -O3 misreads "." + string (-Wrestrict)
  tmp_name.append(path.filename().string());
  tmp_name.append(".tmp-");
  tmp_name.append(std::to_string(::getpid()));
  tmp_name.push_back('-');
  tmp_name.append(std::to_string(counter++));
  const std::filesystem::path tmp = dir / tmp_name;
  const auto fail = [&](const std::string& what, int e) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw std::runtime_error(path.string() + ": " + what + ": " + std::strerror(e) +
                             " (the old file, if any, is unchanged)");
  };
  const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int e = errno;
    throw std::runtime_error(path.string() + ": cannot create the temporary file " + tmp.string() + ": " +
                             std::strerror(e) + " (the old file, if any, is unchanged)");
  }
  std::size_t done = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      const int e = errno;
      ::close(fd);
      fail("write failed", e);
    }
    done += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0) {
    const int e = errno;
    ::close(fd);
    fail("fsync failed", e);
  }
  if (::close(fd) != 0) fail("close failed", errno);
  if (std::rename(tmp.c_str(), path.c_str()) != 0) fail("cannot replace the file", errno);
  // Make the rename itself durable (a power cut must not bring the old file back).
  const int dfd = ::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (dfd >= 0) {
    ::fsync(dfd);
    ::close(dfd);
  }
  remove_stale_temporaries(dir, path.filename().string());
}

std::optional<std::filesystem::path> set_aside_as_bad(const std::filesystem::path& file) {
  std::filesystem::path bad = file;
  bad += ".bad";
  std::error_code ec;
  std::filesystem::rename(file, bad, ec);  // atomic; replaces an older .bad
  if (ec) return std::nullopt;
  return bad;
}

}  // namespace mallet
