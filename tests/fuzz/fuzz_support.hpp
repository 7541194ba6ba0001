#pragma once
// What the file-parser harnesses share: the check every refusal must pass, the shipped
// data they load once, and a scratch file for the readers that take a path.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <system_error>

#include <unistd.h>

#include "core/file_error.hpp"

#ifndef MALLET_FUZZ_SOURCE_DIR
#error "MALLET_FUZZ_SOURCE_DIR (the source tree, for the shipped files) must be defined"
#endif

namespace mallet::fuzz {

//! The input as text, exactly its bytes.
inline std::string_view text_of(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

//! A file of the source tree (config/materials.toml …).
inline std::filesystem::path source_file(const char* relative) {
  return std::filesystem::path(MALLET_FUZZ_SOURCE_DIR) / relative;
}

//! A refusal the program may print: it names the file it was given, starts with it, and
//! is one line (a person reads it in a terminal or the journal). MALLET_FUZZ_PRINT=1 in
//! the environment prints each refusal (to see what a reproducer now gets).
inline void check_refusal(const FileError& e, const std::string& file) {
  const std::string_view what = e.what();
  const char* broken = nullptr;
  if (e.file() != file || what.substr(0, file.size()) != file) broken = "does not name the file";
  else if (what.find_first_of("\n\r") != std::string_view::npos) broken = "is not one line";
  else if (what.size() <= file.size() + 2) broken = "names no problem";  // "FILE: " and then one
  if (broken == nullptr) {
    if (std::getenv("MALLET_FUZZ_PRINT") != nullptr) std::fprintf(stderr, "refused: %s\n", e.what());
    return;
  }
  std::fprintf(stderr, "the refusal %s (expected %s): %s\n", broken, file.c_str(), e.what());
  std::abort();
}

//! A private folder made once per process (mkdtemp), removed at exit, holding the files a
//! harness writes its input to: in $TMPDIR if set, else in memory (/dev/shm) where there is
//! one: on a disk mounted with `discard`, rewriting the file made each run 100 times slower.
class ScratchDir {
 public:
  ScratchDir() {
    std::error_code ec;
    const bool shm = std::getenv("TMPDIR") == nullptr && std::filesystem::is_directory("/dev/shm", ec) &&
                     ::access("/dev/shm", W_OK) == 0;
    const std::filesystem::path base = shm ? std::filesystem::path("/dev/shm") : std::filesystem::temp_directory_path();
    std::string pattern = (base / "mallet-fuzz-XXXXXX").string();
    if (::mkdtemp(pattern.data()) == nullptr) std::abort();
    dir_ = pattern;
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  //! `name` in the folder, holding exactly `bytes` (overwritten).
  std::filesystem::path write(const std::string& name, std::string_view bytes) const {
    const std::filesystem::path path = dir_ / name;
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
    out.close();
    if (!out) std::abort();
    return path;
  }
  void remove(const std::string& name) const {
    std::error_code ec;
    std::filesystem::remove(dir_ / name, ec);
  }
  const std::filesystem::path& path() const { return dir_; }

 private:
  std::filesystem::path dir_;
};

//! The process's scratch folder.
inline const ScratchDir& scratch() {
  static const ScratchDir dir;
  return dir;
}

}  // namespace mallet::fuzz
