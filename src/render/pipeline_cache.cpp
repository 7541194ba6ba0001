#include "render/pipeline_cache.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <iterator>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "core/atomic_file.hpp"
#include "core/journal.hpp"
#include "render/vk_error.hpp"

namespace mallet::render {
namespace fs = std::filesystem;

namespace {

//! A cache file is only offered to the driver when its header names this very device
//! and driver (vendor, device id, pipeline-cache UUID).
bool header_matches(const std::vector<char>& data, const VkPhysicalDeviceProperties& p) {
  VkPipelineCacheHeaderVersionOne header;
  if (data.size() < sizeof(header)) return false;
  std::memcpy(&header, data.data(), sizeof(header));
  return header.headerVersion == VK_PIPELINE_CACHE_HEADER_VERSION_ONE && header.vendorID == p.vendorID &&
         header.deviceID == p.deviceID &&
         std::memcmp(header.pipelineCacheUUID, p.pipelineCacheUUID, VK_UUID_SIZE) == 0;
}

}  // namespace

fs::path PipelineCache::default_dir() {
  if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return fs::path(xdg) / "mallet";
  if (const char* home = std::getenv("HOME"); home && *home) return fs::path(home) / ".cache" / "mallet";
  return {};
}

PipelineCache::PipelineCache(const Context& ctx, fs::path dir) : ctx_(ctx) {
  const VkPhysicalDeviceProperties& p = ctx.properties();
  std::vector<char> data;
  if (!dir.empty()) {
    const std::string name = fmt::format("pipelines-{:04x}-{:04x}-{:08x}.bin", p.vendorID, p.deviceID, p.driverVersion);
    file_ = dir / name;
    std::ifstream in(file_, std::ios::binary);
    if (in) data.assign(std::istreambuf_iterator<char>(in), {});
    if (!header_matches(data, p)) data.clear();
  }
  VkPipelineCacheCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_CACHE_CREATE_INFO};
  ci.initialDataSize = data.size();
  ci.pInitialData = data.empty() ? nullptr : data.data();
  VkPipelineCache raw;
  VkResult r = vkCreatePipelineCache(ctx.device(), &ci, nullptr, &raw);
  if (r != VK_SUCCESS && !data.empty()) {  // a damaged file: start empty
    ci.initialDataSize = 0;
    ci.pInitialData = nullptr;
    data.clear();
    r = vkCreatePipelineCache(ctx.device(), &ci, nullptr, &raw);
  }
  check(r, "creating the pipeline cache");
  cache_ = vk::PipelineCacheHandle(ctx.device(), raw);
  loaded_ = !data.empty();
}

PipelineCache::~PipelineCache() { save(); }

void PipelineCache::save() const {
  if (file_.empty()) return;
  std::size_t size = 0;
  if (vkGetPipelineCacheData(ctx_.device(), cache_.get(), &size, nullptr) != VK_SUCCESS || size == 0) return;
  std::vector<char> data(size);
  if (vkGetPipelineCacheData(ctx_.device(), cache_.get(), &size, data.data()) != VK_SUCCESS) return;
  std::error_code ec;
  fs::create_directories(file_.parent_path(), ec);
  // Through a temporary file of this process's own: two programs closing at once (tests, a
  // render beside the kiosk) each put a whole file in place, and the last one stays.
  try {
    write_file_atomically(file_, std::string_view(data.data(), size));
  } catch (const std::exception& e) {
    journal::warning("cannot save the pipeline cache (next start compiles again): {}", e.what());
  }
}

}  // namespace mallet::render
