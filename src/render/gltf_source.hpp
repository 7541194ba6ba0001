#pragma once
// What the glTF loader reads, checked before tinygltf sees it. A kiosk loads models at
// start-up and on every reload, from files an operator or a museum's modeller supplies; a
// hostile or unlucky file must be refused with one line, never crash, hang or exhaust
// memory. tinygltf alone does not promise that:
// * its default file access opens a FIFO (and blocks forever) and "reads" a directory as a
//   file of absurd size (std::bad_alloc);
// * its JSON values are converted recursively, so deep nesting overflows the stack;
// * a compressed mesh (Draco, meshopt) fails on an accessor, never naming the compression.
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace tinygltf {
class TinyGLTF;
}

namespace mallet::render {

//! The largest file the loader reads (the model, or a buffer or image it names): far above
//! a detailed instrument model (a 75k-triangle .glb is ≈ 4 MiB), and a bound on memory.
inline constexpr std::uintmax_t kMaxGltfFileBytes = 512ull << 20;
//! JSON nesting deeper than this is refused: glTF's own structure is at most 6 deep; the
//! rest is room for `extras`.
inline constexpr int kMaxGltfJsonDepth = 64;

//! The whole of `file`, if it is a regular file no larger than kMaxGltfFileBytes; otherwise
//! FileError "FILE: problem" (no such file, a directory, a FIFO or device, too large,
//! unreadable). Never opens anything but a regular file.
std::vector<unsigned char> read_gltf_file(const std::filesystem::path& file);

//! Why `path` cannot be read as a glTF part ("is a directory" …), or nothing when it can.
std::optional<std::string> unreadable_reason(const std::filesystem::path& path);

//! Makes `reader` open external buffers and images as read_gltf_file does (regular files
//! only, size-bounded), never expand paths, and never write.
void use_guarded_files(tinygltf::TinyGLTF& reader);

//! The JSON text of a .gltf, or the JSON chunk of a .glb (empty when the header is too
//! short to say; tinygltf then reports the file itself).
std::string_view gltf_json_text(std::span<const unsigned char> bytes, bool binary);

//! Throws FileError naming FILE:LINE:COLUMN of the JSON (for a .glb: of its JSON chunk)
//! where arrays and objects nest deeper than kMaxGltfJsonDepth.
void check_json_nesting(std::string_view json, const std::string& file, bool binary);

//! A mesh compression extension the JSON names, with its common name ("Draco"), if any:
//! the loader cannot decode them.
std::optional<std::string> mesh_compression(std::string_view json);

}  // namespace mallet::render
