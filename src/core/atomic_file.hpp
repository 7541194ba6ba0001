#pragma once
// Replacing a file so that a reader never sees half of it and a power cut leaves either the
// old or the new file: write a temporary file in the same folder (unique per process and
// call), fsync it, rename it over the target, fsync the folder. The folder is not created.
#include <filesystem>
#include <string_view>

namespace mallet {

//! Throws std::runtime_error "FILE: what failed: why (the old file, if any, is unchanged)".
void write_file_atomically(const std::filesystem::path& path, std::string_view bytes);

}  // namespace mallet
