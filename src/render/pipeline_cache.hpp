#pragma once
// The Vulkan pipeline cache, persisted between runs so the kiosk starts fast after the
// first: loaded from a file named after the device and driver (a cache from another
// device or driver version is ignored, never trusted), saved atomically on exit.
#include <filesystem>

#include "render/vk_context.hpp"

namespace mallet::render {

class PipelineCache {
 public:
  //! `dir` empty: an in-memory cache that is never saved.
  PipelineCache(const Context& ctx, std::filesystem::path dir);
  ~PipelineCache();  //!< saves (errors are reported on stderr, never thrown)
  PipelineCache(const PipelineCache&) = delete;
  PipelineCache& operator=(const PipelineCache&) = delete;

  VkPipelineCache get() const { return cache_.get(); }
  bool loaded_from_disk() const { return loaded_; }
  const std::filesystem::path& file() const { return file_; }
  void save() const;

  //! $XDG_CACHE_HOME/mallet, else $HOME/.cache/mallet, else empty (no persistence).
  static std::filesystem::path default_dir();

 private:
  const Context& ctx_;
  std::filesystem::path file_;
  vk::PipelineCacheHandle cache_;
  bool loaded_ = false;
};

}  // namespace mallet::render
