#pragma once
// Everything a headless frame needs, in one owner: the Vulkan context, the persisted
// pipeline cache, the scene renderer and an offscreen target. Used by `mallet render`,
// `mallet bench render`, the golden tests and the headless kiosk.
#include <filesystem>
#include <memory>
#include <string>

#include "core/scene.hpp"
#include "render/offscreen_target.hpp"
#include "render/pipeline_cache.hpp"
#include "render/scene_renderer.hpp"
#include "render/vk_context.hpp"

namespace mallet::app {

//! MALLET_VK_VALIDATION: "0" off, "1" if available, "required"; unset: on (if
//! available) in Debug builds, off otherwise.
render::Validation validation_from_env();

//! "1280x720" → {1280, 720}; throws FileError naming `option` otherwise.
VkExtent2D parse_size(const std::string& text, const std::string& option);

struct HeadlessOptions {
  VkExtent2D size{1280, 720};
  render::RenderSettings settings;
  bool auto_samples = false;          //!< replace settings.samples by render::recommended_samples
  std::string device;                 //!< substring of the Vulkan device name; empty = best
  render::Validation validation = validation_from_env();
  std::filesystem::path cache_dir = render::PipelineCache::default_dir();
};

class HeadlessRenderer {
 public:
  HeadlessRenderer(const Scene& scene, const HeadlessOptions& options);
  ~HeadlessRenderer();

  render::Image render(const render::FrameState& state) { return target_->render(*renderer_, state); }
  void draw(const render::FrameState& state) { target_->draw(*renderer_, state); }
  render::Image read_back() const { return target_->read_back(); }

  render::Context& context() { return *ctx_; }
  render::SceneRenderer& renderer() { return *renderer_; }
  const render::PipelineCache& pipeline_cache() const { return *cache_; }

 private:
  std::unique_ptr<render::Context> ctx_;
  std::unique_ptr<render::PipelineCache> cache_;
  std::unique_ptr<render::SceneRenderer> renderer_;
  std::unique_ptr<render::OffscreenTarget> target_;
};

//! The shipped models: DATA/models.
std::filesystem::path models_dir();

}  // namespace mallet::app
