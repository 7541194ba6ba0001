#include "app/render_setup.hpp"

#include <cstdlib>
#include <regex>

#include "app/data_paths.hpp"
#include "core/file_error.hpp"

namespace mallet::app {

render::Validation validation_from_env() {
  const char* v = std::getenv("MALLET_VK_VALIDATION");
  if (v && std::string(v) == "required") return render::Validation::required;
  if (v && *v) return std::string(v) == "0" ? render::Validation::off : render::Validation::if_available;
#ifdef NDEBUG
  return render::Validation::off;
#else
  return render::Validation::if_available;
#endif
}

VkExtent2D parse_size(const std::string& text, const std::string& option) {
  static const std::regex form("([0-9]{1,5})x([0-9]{1,5})");
  std::smatch m;
  if (!std::regex_match(text, m, form))
    throw FileError(option, 0, 0, "expected WIDTHxHEIGHT such as 1280x720, got \"" + text + "\"");
  const unsigned long w = std::stoul(m[1]), h = std::stoul(m[2]);
  if (w < 16 || h < 16 || w > 8192 || h > 8192)
    throw FileError(option, 0, 0, "width and height must be 16..8192, got " + text);
  return {static_cast<std::uint32_t>(w), static_cast<std::uint32_t>(h)};
}

std::filesystem::path models_dir() { return data_dir() / "models"; }

HeadlessRenderer::HeadlessRenderer(const Scene& scene, const HeadlessOptions& options) {
  render::ContextOptions co;
  co.validation = options.validation;
  co.device_name = options.device;
  ctx_ = std::make_unique<render::Context>(co);
  cache_ = std::make_unique<render::PipelineCache>(*ctx_, options.cache_dir);
  renderer_ = std::make_unique<render::SceneRenderer>(*ctx_, scene, models_dir(), render::OffscreenTarget::kFormat,
                                                      options.settings, cache_->get());
  target_ = std::make_unique<render::OffscreenTarget>(*ctx_, options.size);
}

HeadlessRenderer::~HeadlessRenderer() {
  target_.reset();
  renderer_.reset();
  cache_.reset();  // saves the cache
  ctx_.reset();
}

}  // namespace mallet::app
