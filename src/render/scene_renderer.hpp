#pragma once
// Draws one frame of a scene into a colour image: the instruments from their glTF
// models, the mallet head with its analytic cast shadow, and the 2D overlay. Shared by
// the offscreen target (goldens, `mallet render`, headless kiosk) and the window target.
//
// Per frame the caller gives the displayed mallet centre (the contact solver's
// displayed position plus the visual vibration evaluated at the frame's predicted
// present time); it is written into the per-frame uniform buffer of the frame's slot.
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "core/geometry.hpp"
#include "core/scene.hpp"
#include "render/gpu_resources.hpp"
#include "render/overlay.hpp"
#include "render/scene_view.hpp"

namespace mallet::render {

struct RenderSettings {
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;  //!< antialiasing: MSAA sample count
  bool shadow = true;                                     //!< the sphere's analytic shadow
  std::array<float, 3> clear_color{0.018f, 0.018f, 0.022f};  //!< linear; a dark room
};

struct FrameState {
  Vec2 mallet_centre;               //!< world metres, plane z = 0, as displayed
  bool draw_mallet = true;
  bool draw_instruments = true;      //!< false: only the clear (the benchmark's floor)
  const Overlay* overlay = nullptr;  //!< drawn last, over everything; may be null
};

//! Whether the device can render colour and depth with this many samples per pixel.
bool supports_samples(const Context& ctx, VkSampleCountFlagBits samples);

//! Antialiasing chosen by measurement (`mallet bench render`, README): on a CPU rasteriser
//! (lavapipe) 4x MSAA costs ≈3–4x the frame for an RMS error against a supersampled
//! reference of ≈1.1 instead of ≈2.2 (1/255 units), too dear for 60 fps: none there;
//! on a GPU, 4x MSAA.
VkSampleCountFlagBits recommended_samples(const Context& ctx);

class SceneRenderer {
 public:
  static constexpr std::uint32_t kSlots = 2;  //!< frames in flight

  //! Loads every model the scene names from `models_dir` (FileError if one is missing or
  //! malformed: nothing is drawn from a broken model) and builds the pipelines.
  SceneRenderer(const Context& ctx, const Scene& scene, const std::filesystem::path& models_dir,
                VkFormat color_format, RenderSettings settings, VkPipelineCache cache);
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  //! Records a whole frame into `target` (colour_format, `extent`), whose content is
  //! discarded, and leaves it in `final_layout`. `slot` < kSlots selects the per-frame
  //! buffers; the caller makes sure the GPU is done with that slot's previous frame.
  void record(VkCommandBuffer cmd, VkImage target, VkImageView target_view, VkExtent2D extent,
              VkImageLayout final_layout, VkPipelineStageFlags2 final_stage, VkAccessFlags2 final_access,
              const FrameState& state, std::uint32_t slot);

  const RenderSettings& settings() const { return settings_; }
  const glm::mat4& view_projection() const { return view_proj_; }
  std::size_t triangle_count() const;

 private:
  struct GpuMaterial {
    std::array<float, 4> base_color{};
    float metallic = 0, roughness = 1;
    bool textured = false;
    VkDescriptorSet set = VK_NULL_HANDLE;
  };
  struct GpuPrimitive {
    std::uint32_t first_index = 0, index_count = 0;
    std::int32_t vertex_offset = 0;
    int material = 0;
  };
  struct GpuModel {
    GpuBuffer vertices, indices;
    std::vector<GpuPrimitive> primitives;
    std::vector<GpuMaterial> materials;
    std::vector<GpuImage> textures;
  };
  struct Slot {
    GpuBuffer frame_uniform;
    VkDescriptorSet frame_set = VK_NULL_HANDLE;
    GpuBuffer overlay_vertices, overlay_indices;
  };

  void load_model(const std::filesystem::path& file, const std::string& name);
  void build_pipelines(VkPipelineCache cache);
  void ensure_attachments(VkExtent2D extent);
  void ensure_atlas(const FontAtlas& atlas);
  void draw_instance(VkCommandBuffer cmd, const Instance& instance, bool receives_shadow);
  void draw_overlay(VkCommandBuffer cmd, const Overlay& overlay, Slot& slot, VkExtent2D extent);
  VkDescriptorSet allocate_set(VkDescriptorSetLayout layout);
  void write_image_set(VkDescriptorSet set, VkImageView view);

  const Context& ctx_;
  const Scene& scene_;
  VkFormat color_format_;
  RenderSettings settings_;
  glm::mat4 view_proj_;
  std::vector<Instance> instruments_;
  std::map<std::string, GpuModel> models_;
  GpuImage white_;
  vk::Sampler sampler_;
  vk::DescriptorSetLayout frame_layout_, image_layout_;
  vk::DescriptorPool pool_;
  vk::PipelineLayout scene_pipeline_layout_, overlay_pipeline_layout_;
  vk::Pipeline scene_pipeline_, overlay_pipeline_;
  std::array<Slot, kSlots> slots_;
  VkExtent2D attachment_extent_{};
  GpuImage depth_, msaa_color_;
  const FontAtlas* atlas_source_ = nullptr;
  GpuImage atlas_;
  VkDescriptorSet atlas_set_ = VK_NULL_HANDLE;
};

}  // namespace mallet::render
