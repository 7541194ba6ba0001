#pragma once
// The kiosk's writes into its state folder (state_dir(): /var/lib/mallet under the unit):
// the calibration, the last good settings, the count of starts, the visitor study's
// results. Every write replaces its file atomically (core/atomic_file: a temporary file
// renamed over it), so a full disk (ENOSPC), a read-only file system (EROFS) or a folder
// the kiosk may not write (EACCES) leaves the previous file whole; and a write that fails
// never ends or stalls the kiosk: it plays on, keeping nothing new, and says so once —
// one journal warning naming the folder, the file, why and the free space, not one a
// write — and, while it lasts, one line on the operator page and a `fail disk` in the
// doctor's view. The first write that succeeds again says that too.
//
// Main thread only (the frame loop, its calibration screen and visitor sessions).
#include <sys/statvfs.h>

#include <cstdint>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/result.hpp"

namespace mallet::app {

//! Bytes free to an unprivileged writer on the file system that holds `path` (or its
//! nearest existing parent: the folder may not exist yet); none when it cannot be read.
inline std::optional<std::uint64_t> free_bytes(std::filesystem::path path) {
  std::error_code ec;
  while (!path.empty() && !std::filesystem::exists(path, ec) && path != path.parent_path()) path = path.parent_path();
  struct statvfs st {};
  if (path.empty() || ::statvfs(path.c_str(), &st) != 0) return std::nullopt;
  return static_cast<std::uint64_t>(st.f_bavail) * st.f_frsize;
}

//! "12.0 MiB" / "71.2 GiB".
inline std::string bytes_text(std::uint64_t bytes) {
  const double mib = static_cast<double>(bytes) / (1024.0 * 1024.0);
  return mib >= 1024.0 ? fmt::format("{:.1f} GiB", mib / 1024.0) : fmt::format("{:.1f} MiB", mib);
}

class StateFolder {
 public:
  using Log = std::function<void(const std::string& line)>;
  //! `warn` gets the first failure (once until a write succeeds), `note` the recovery.
  StateFolder(std::filesystem::path dir, Log warn, Log note)
      : dir_(std::move(dir)), warn_(std::move(warn)), note_(std::move(note)) {}

  const std::filesystem::path& dir() const { return dir_; }
  std::filesystem::path file(const std::string& name) const { return dir_ / name; }

  //! Replaces dir/name with `bytes` atomically, the folder created first. Never throws:
  //! a failure is reported (wrote()) and the previous file stays as it was.
  Check write(const std::string& name, std::string_view bytes) {
    Check done;
    try {
      std::error_code ec;
      std::filesystem::create_directories(dir_, ec);  // a failure shows in the write, with its reason
      write_file_atomically(file(name), bytes);
    } catch (const std::exception& e) {
      done = refused(e.what());
    }
    wrote(name, done);
    return done;
  }

  //! A write into the folder made elsewhere (the calibration screen's, the visitor study's):
  //! `what` names it, `outcome` its result (its refusal: the one-line reason).
  void wrote(const std::string& what, const Check& outcome) {
    if (outcome) {
      if (!problem_.empty()) note_(fmt::format("state folder {}: writing again ({} written)", dir_.string(), what));
      problem_.clear();
      return;
    }
    const std::optional<std::uint64_t> space = free_bytes(dir_);
    // The reason names the file already when it comes from write_file_atomically.
    const std::string& why = outcome.error();
    std::string line = fmt::format("state folder {} cannot be written ({} free): {}; the kiosk plays on and keeps "
                                   "nothing new until it can",
                                   dir_.string(), space ? bytes_text(*space) : std::string("unknown"),
                                   why.find(what) != std::string::npos ? why : what + ": " + why);
    if (problem_.empty()) warn_(line);  // once a failing spell, not once a write
    problem_ = std::move(line);
  }

  bool failing() const { return !problem_.empty(); }
  //! The last failure's line (for the operator page and the doctor); empty while writes succeed.
  const std::string& problem() const { return problem_; }

 private:
  std::filesystem::path dir_;
  Log warn_, note_;
  std::string problem_;
};

}  // namespace mallet::app
