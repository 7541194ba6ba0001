#pragma once
// How the input layer's device nodes (evdev, V4L2) say what went wrong: errno's words,
// thread-safe (std::strerror is not: a reading thread and an open may run at once), and an
// open refused for permissions with the group that grants it.
#include <cerrno>
#include <string>
#include <system_error>

namespace mallet::input {

//! errno's words, e.g. "No such device".
inline std::string errno_text(int err) { return std::error_code(err, std::generic_category()).message(); }

//! "/dev/video0: Permission denied (is the user in the 'video' group?)": a node that could
//! not be opened; the hint only for EACCES and EPERM.
inline std::string open_error(const std::string& path, int err, const char* group) {
  std::string out = path + ": " + errno_text(err);
  if (err == EACCES || err == EPERM) out += std::string(" (is the user in the '") + group + "' group?)";
  return out;
}

}  // namespace mallet::input
