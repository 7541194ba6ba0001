#include "render/gltf_source.hpp"

#include <array>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <system_error>
#include <utility>

#include <tiny_gltf.h>

#include "core/file_error.hpp"

namespace mallet::render {
namespace fs = std::filesystem;

std::optional<std::string> unreadable_reason(const fs::path& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);  // follows links; opens nothing
  if (ec || !fs::exists(status)) return std::string("no such file");
  if (fs::is_directory(status)) return std::string("is a directory, not a file");
  if (!fs::is_regular_file(status)) return std::string("is not a regular file (a FIFO, socket or device)");
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) return "cannot read its size: " + ec.message();
  if (size > kMaxGltfFileBytes)
    return "is " + std::to_string(size >> 20) + " MiB, larger than the " + std::to_string(kMaxGltfFileBytes >> 20) +
           " MiB Mallet loads";
  return std::nullopt;
}

namespace {

//! The file's bytes, or the reason they cannot be had.
std::optional<std::string> read_guarded(const fs::path& path, std::vector<unsigned char>& out) {
  if (std::optional<std::string> why = unreadable_reason(path)) return why;
  std::ifstream in(path, std::ios::binary);
  if (!in) return std::string("cannot be opened for reading");
  out.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (in.bad()) return std::string("read error");
  if (out.size() > kMaxGltfFileBytes) return std::string("grew past the size Mallet loads while being read");
  return std::nullopt;
}

bool exists_without_opening(const std::string& path, void*) {
  std::error_code ec;
  return fs::exists(path, ec);  // a directory or FIFO "exists": reading it says what it is
}

std::string path_as_is(const std::string& path, void*) { return path; }  // no ~ or $VAR expansion

bool read_part(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  const std::optional<std::string> why = read_guarded(path, *out);
  if (why && err != nullptr) *err += *why;
  return !why;
}

bool never_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err != nullptr) *err += "the loader never writes files";
  return false;
}

//! tinygltf 2.8 and later ask a part's size before reading it (Debian 13's 2.9.5). A part
//! that cannot be read answers 0, so that read_part says why, in the words Debian 12's loader
//! gives ("File read error : PATH : is a directory, not a file"), whichever tinygltf runs.
//! (Unused with 2.7: only hand_over's branch for 2.8 and later names it.)
[[maybe_unused]] bool size_without_opening(std::size_t* size, std::string*, const std::string& path, void*) {
  std::error_code ec;
  *size = unreadable_reason(path) ? 0 : static_cast<std::size_t>(fs::file_size(path, ec));
  if (ec) *size = 0;
  return true;
}

//! Debian 12's tinygltf 2.7 has no size callback, and its SetFsCallbacks returns nothing;
//! Debian 13's 2.9 wants every callback set, else it keeps its own (which open a FIFO and
//! wait for ever), and says so only through its return value.
template <class Callbacks>
void hand_over(tinygltf::TinyGLTF& reader, Callbacks callbacks) {
  if constexpr (requires { callbacks.GetFileSizeInBytes = &size_without_opening; }) {
    callbacks.GetFileSizeInBytes = &size_without_opening;
    std::string err;
    if (!reader.SetFsCallbacks(callbacks, &err))
      throw std::logic_error("tinygltf refused the guarded file callbacks: " + err);
  } else {
    reader.SetFsCallbacks(callbacks);
  }
}

}  // namespace

std::vector<unsigned char> read_gltf_file(const fs::path& file) {
  std::vector<unsigned char> bytes;
  if (const std::optional<std::string> why = read_guarded(file, bytes)) throw FileError(file.string(), 0, 0, *why);
  return bytes;
}

void use_guarded_files(tinygltf::TinyGLTF& reader) {
  tinygltf::FsCallbacks callbacks{};
  callbacks.FileExists = &exists_without_opening;
  callbacks.ExpandFilePath = &path_as_is;
  callbacks.ReadWholeFile = &read_part;
  callbacks.WriteWholeFile = &never_write;
  callbacks.user_data = nullptr;
  hand_over(reader, callbacks);
}

std::string_view gltf_json_text(std::span<const unsigned char> bytes, bool binary) {
  const auto* text = reinterpret_cast<const char*>(bytes.data());
  if (!binary) return {text, bytes.size()};
  // 12-byte header, then the first chunk: its length, its type ("JSON"), its data.
  if (bytes.size() < 20 || std::memcmp(bytes.data() + 16, "JSON", 4) != 0) return {};
  std::uint32_t length = 0;
  std::memcpy(&length, bytes.data() + 12, sizeof length);  // little-endian, as glTF
  return {text + 20, std::min<std::size_t>(length, bytes.size() - 20)};
}

void check_json_nesting(std::string_view json, const std::string& file, bool binary) {
  int depth = 0;
  bool in_string = false;
  bool escaped = false;
  std::uint32_t line = 1;
  std::uint32_t column = 0;
  for (const char c : json) {
    ++column;
    if (c == '\n') {
      ++line;
      column = 0;
    }
    if (in_string) {
      if (escaped) {
        escaped = false;
      } else if (c == '\\') {
        escaped = true;
      } else if (c == '"') {
        in_string = false;
      }
      continue;
    }
    if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxGltfJsonDepth) {
        const std::string problem = "JSON nested more than " + std::to_string(kMaxGltfJsonDepth) +
                                    " arrays or objects deep (glTF needs 6; deeper is refused)";
        if (binary)
          throw FileError(file, 0, 0,
                          "JSON chunk line " + std::to_string(line) + " column " + std::to_string(column) + ": " +
                              problem);
        throw FileError(file, line, column, problem);
      }
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

std::optional<std::string> mesh_compression(std::string_view json) {
  static constexpr std::array<std::pair<std::string_view, std::string_view>, 3> kCompressions{{
      {"KHR_draco_mesh_compression", "Draco"},
      {"EXT_meshopt_compression", "meshopt"},
      {"KHR_meshopt_compression", "meshopt"},
  }};
  for (const auto& [extension, name] : kCompressions)
    if (json.find(extension) != std::string_view::npos) return std::string(extension) + " (" + std::string(name) + ")";
  return std::nullopt;
}

}  // namespace mallet::render
