#pragma once
// Replacing a file so that a reader never sees half of it and a power cut leaves either the
// old or the new file: write a temporary file in the same folder (unique per process and
// call), fsync it, rename it over the target, fsync the folder. The folder is not created.
// A process killed mid-write (SIGKILL, a power cut) leaves the old file whole and, at most,
// its temporary file, which the next write of the same file removes.
#include <filesystem>
#include <optional>
#include <string_view>

namespace mallet {

//! Throws std::runtime_error "FILE: what failed: why (the old file, if any, is unchanged)".
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

//! A state file that cannot be used (corrupt, from another version) is kept for the operator
//! beside where it was, as FILE.bad (an older FILE.bad is replaced), so that the program can
//! go on from its defaults and write a good FILE later. Returns the new name, or nothing when
//! the file cannot be moved (a read-only folder): it then stays where it is.
std::optional<std::filesystem::path> set_aside_as_bad(const std::filesystem::path& file);

}  // namespace mallet
