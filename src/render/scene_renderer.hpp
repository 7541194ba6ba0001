#pragma once
// Draws one frame of a scene into a colour image: the instruments from their glTF
// models, the mallet head with its analytic cast shadow, and the 2D overlay. Shared by
// the offscreen target (goldens, `mallet render`, headless kiosk) and the window target.
//
// The camera never moves and neither do the instruments, so they are drawn once per image
// size into a cached background (colour and depth, and at one sample a pixel each pixel's
// light and bar: gbuffer.frag). Each frame copies it in, changes the instruments only inside
// the rectangle the mallet's shadow can reach (shadow_bounds) and on the lit bars (shaded on
// the screen from the cached light, shadow.frag, whatever the models' triangles; for bars
// of few triangles, their glow added over them, glow.frag; for multisampled frames,
// redrawn), and draws the mallet over it,
// depth-tested against the cached depth: the pixels of drawing the whole scene (a test
// compares them: to 1/255 on the screen, exactly when redrawn), at a small part of the cost
// on a CPU rasteriser (`mallet bench render`). The mallet is drawn there without writing depth (the
// cache's), so its model must hide its own back by culling alone: convex, as the sphere is.
// Its model is a hull (drawn kMalletHullScale larger), shaded as the exact sphere of the
// scene's radius and blended over by each pixel's coverage (sphere.frag): a smooth ball with
// an antialiased edge at one sample a pixel. The model gives its material, not its shape.
//
// Per frame the caller gives the displayed mallet centre (the contact solver's
// displayed position plus the visual vibration evaluated at the frame's predicted
// present time); it is written into the per-frame uniform buffer of the frame's slot.
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <vulkan/vulkan.h>

#include "core/bar_lights.hpp"
#include "core/geometry.hpp"
#include "core/scene.hpp"
#include "render/gpu_resources.hpp"
#include "render/frame_damage.hpp"
#include "render/overlay.hpp"
#include "render/scene_view.hpp"

namespace mallet::render {

struct RenderSettings {
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;  //!< antialiasing: MSAA sample count
  bool shadow = true;                                     //!< the sphere's analytic shadow
  std::array<float, 3> clear_color{0.018f, 0.018f, 0.022f};  //!< linear; a dark room
  bool background_cache = true;  //!< false: every frame draws the whole scene (for comparison)
  //! With samples = 1: the cached background's own MSAA, paid once per image size and
  //! resolved into it, so the instruments' edges are antialiased at no cost per frame (the
  //! mallet and the shadowed pixels are drawn with the frame's 1 sample). Ignored when the
  //! device does not offer it, and when samples > 1 (the background then has the frame's).
  VkSampleCountFlagBits background_samples = VK_SAMPLE_COUNT_1_BIT;
};

//! The image a frame is drawn into, and what it is left ready for.
struct FrameTarget {
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkExtent2D extent{};
  bool copy_destination = false;  //!< made with TRANSFER_DST: the background is copied into it
  VkImageLayout final_layout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkPipelineStageFlags2 final_stage = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 final_access = VK_ACCESS_2_NONE;
  //! The image still holds what this renderer last drew into it (a window's swapchain image
  //! it showed before), in `kept_layout`: a frame over the cached background then draws only
  //! what changed since (render/frame_damage.hpp). False: drawn whole.
  bool kept = false;
  VkImageLayout kept_layout = VK_IMAGE_LAYOUT_UNDEFINED;
};

//! The stages at which a frame first touches its target (the background's copy, or the
//! colour attachment's clear): a semaphore the frame waits on must wait there.
inline constexpr VkPipelineStageFlags2 kTargetFirstUse =
    VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_2_COPY_BIT;

struct FrameState {
  Vec2 mallet_centre;               //!< world metres, plane z = 0, as displayed
  bool draw_mallet = true;
  bool draw_instruments = true;      //!< false: only the clear (the benchmark's floor)
  const Overlay* overlay = nullptr;  //!< drawn last, over everything; may be null
  //! Bars lit this frame (core/bar_lights.hpp): the one under the mallet, the one struck,
  //! one the screen points a visitor to.
  BarLights bar_lights{};
};

//! Whether the device can render colour and depth with this many samples per pixel.
bool supports_samples(const Context& ctx, VkSampleCountFlagBits samples);

//! Antialiasing chosen by measurement (`mallet bench render`, docs/researchers.md): on a CPU rasteriser
//! (lavapipe) 4x MSAA on every frame costs ≈10x the frame drawn over the cached background,
//! but the background's own 4x MSAA (drawn once) brings the 1080p image's RMS error against
//! a supersampled reference from 1.77 to 0.90 (1/255; whole-frame 4x MSAA: 0.85) at no cost
//! per frame: frames 1x, background 4x there; on a GPU, 4x MSAA for everything.
VkSampleCountFlagBits recommended_samples(const Context& ctx);
void use_recommended_antialiasing(const Context& ctx, RenderSettings& settings);

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

  //! Records a whole frame into `target` (colour_format), whose content is discarded, and
  //! leaves it in its final layout. `slot` < kSlots selects the per-frame buffers; the
  //! caller makes sure the GPU is done with that slot's previous frame.
  void record(VkCommandBuffer cmd, const FrameTarget& target, const FrameState& state, std::uint32_t slot);
  //! Whether a frame of `state` at `extent` would differ from the last one recorded: when
  //! not, the picture a window shows is already right and need not be drawn.
  bool changes(const FrameState& state, VkExtent2D extent) const;
  //! The pixels the last frame recorded drew: the image's whole, or on a kept image the part
  //! that changed since it was last drawn into.
  PixelRect last_drawn_area() const { return drawn_area_; }

  const RenderSettings& settings() const { return settings_; }
  //! For the image size last recorded (the scene's own proportions before the first frame).
  const glm::mat4& view_projection() const { return view_proj_; }
  std::size_t triangle_count() const;
  //! How many times the cached background was drawn: once per image size it met.
  std::uint64_t background_builds() const { return background_builds_; }
  //! How often glyphs added to the overlay's atlas were copied into its texture in place.
  std::uint64_t atlas_updates() const { return atlas_updates_; }
  //! How many passes the last frame drew over the cached background for the sphere's
  //! shadow and the lit detailed bars. Single-sampled frames (a CPU rasteriser's): shaded on
  //! the screen from the cached light, bars and depth, one pass over each rectangle that
  //! changes (the shadow's; each lit bar's with more than 1000 triangles, kRedrawLitBarTriangles,
  //! whose glow would cost more to redraw), whatever the models' triangles. Multisampled frames (a
  //! GPU's), whose bar edges need each sample's coverage: one per instrument whose screen box
  //! meets the shadow's rectangle, redrawn. 0: nothing changed (a lit shipped bar's glow,
  //! added over its triangles or redrawn with them, is not counted).
  std::size_t shadow_passes() const { return shadow_passes_; }
  //! Whether the shadow is shaded on the screen (single-sampled frames over the cache).
  bool screen_space_shadow() const {
    return settings_.background_cache && settings_.samples == VK_SAMPLE_COUNT_1_BIT;
  }
  std::size_t instrument_count() const { return instruments_.size(); }

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
    Box bounds;  //!< of its vertices, model space
    GpuBuffer vertices, indices;
    std::vector<GpuPrimitive> primitives;
    std::vector<GpuMaterial> materials;
    std::vector<GpuImage> textures;
  };
  struct Slot {
    GpuBuffer frame_uniform;
    VkDescriptorSet frame_set = VK_NULL_HANDLE;
    GpuBuffer overlay_vertices, overlay_indices;
    GpuBuffer atlas_staging;  //!< the atlas's texels as this slot's frame copies them to the GPU
  };

  void load_model(const std::filesystem::path& file, const std::string& name);
  void build_pipelines(VkPipelineCache cache);
  void ensure_attachments(VkExtent2D extent);
  //! The atlas's texture as `atlas` is now: made for a new atlas, else its added glyphs copied
  //! in by `cmd` (outside any rendering), never replaced while a frame may sample it.
  void ensure_atlas(VkCommandBuffer cmd, const FontAtlas& atlas, Slot& slot);
  void record_background(VkCommandBuffer cmd, const Slot& slot, std::uint32_t slot_index);
  //! The cached instruments' light per pixel and depth (screen_space_shadow()).
  void record_cached_light(VkCommandBuffer cmd, const Slot& slot);
  std::uint32_t triangles_of(const Instance& instance) const;
  //! What a frame of `state` shows over the cached instruments (FrameDamage's terms); its
  //! rectangles only when `extent` is the attachments' size.
  FrameLook look_of(const FrameState& state, VkExtent2D extent) const;
  //! Where the sphere's shadow can change the instruments (shadow_bounds), at the attachments' size.
  PixelRect shadow_rect(const FrameState& state) const;
  //! The shader's params.z: whether a draw receives the sphere's shadow, and whether it is
  //! the redraw over the cached background, which keeps only the pixels the shadow darkens.
  //! the_sphere: the mallet itself, which receives none and is projected as seen from
  //! straight in front of it (sphere_view_projection), so that it is drawn round.
  enum class Shadow { the_sphere = -1, none = 0, receives = 1, only_shadowed_pixels = 2 };
  VkSampleCountFlagBits background_samples() const {
    return settings_.samples != VK_SAMPLE_COUNT_1_BIT ? settings_.samples : settings_.background_samples;
  }
  //! `emissive` (linear): light the bar gives off (a lit bar), added to its shading.
  void draw_instance(VkCommandBuffer cmd, const Instance& instance, Shadow shadow, glm::vec3 emissive = glm::vec3(0.0f));
  void draw_overlay(VkCommandBuffer cmd, const Overlay& overlay, Slot& slot, VkExtent2D extent);
  VkDescriptorSet allocate_set(VkDescriptorSetLayout layout);
  //! `sampler`: the scene's own (repeating, linear) unless another is given.
  void write_image_set(VkDescriptorSet set, VkImageView view, VkSampler sampler = VK_NULL_HANDLE);

  const Context& ctx_;
  const Scene& scene_;
  VkFormat color_format_;
  RenderSettings settings_;
  glm::mat4 view_proj_;
  std::vector<Instance> instruments_;
  std::map<std::string, GpuModel> models_;
  GpuImage white_;
  vk::Sampler sampler_, nearest_sampler_, atlas_sampler_;
  vk::DescriptorSetLayout frame_layout_, image_layout_, shadow_layout_;
  vk::DescriptorPool pool_;
  vk::PipelineLayout scene_pipeline_layout_, overlay_pipeline_layout_, shadow_pipeline_layout_;
  vk::Pipeline scene_pipeline_, overlay_pipeline_;
  vk::Pipeline over_background_pipeline_;  //!< depth-tested against the cached depth, never writing it
  vk::Pipeline light_pipeline_;   //!< the cached light per pixel (gbuffer.frag), one sample a pixel
  vk::Pipeline shadow_pipeline_;  //!< the shadow over the cached background, shaded on the screen
  vk::Pipeline glow_pipeline_;    //!< a lit bar's glow added over it (glow.frag), single-sampled frames
  vk::Pipeline sphere_pipeline_;  //!< the mallet head's hull shaded as the exact sphere (sphere.frag), blended
  vk::Pipeline background_pipeline_;       //!< at background_samples, when they differ from the frames' 
  std::array<Slot, kSlots> slots_;
  VkExtent2D attachment_extent_{};
  GpuImage depth_, msaa_color_;
  Box instruments_box_;                         //!< world bounds of everything that receives the shadow
  std::vector<Box> instrument_boxes_;           //!< each of instruments_', world metres
  std::vector<PixelRect> instrument_rects_;     //!< each of instruments_' on the image (attachment_extent_)
  GpuImage background_color_, background_depth_;  //!< the instruments alone, at attachment_extent_
  GpuImage background_msaa_color_, background_msaa_depth_;  //!< drawn into, then resolved (background_samples)
  //! The cached instruments' light per pixel, unshadowed and the share a full shadow takes
  //! (linear), and their depth: shadow.frag's inputs, at attachment_extent_.
  GpuImage light_unshadowed_, light_share_, light_depth_;
  VkDescriptorSet shadow_set_ = VK_NULL_HANDLE;
  std::optional<std::uint32_t> background_scratch_slot_;   //!< the slot of the frame that drew them
  bool background_ready_ = false;
  std::uint64_t background_builds_ = 0;
  std::size_t shadow_passes_ = 0;
  FrameDamage damage_;
  std::map<VkImage, std::uint64_t> drawn_into_;  //!< each kept image: the frame (damage_'s count) it holds
  std::uint64_t frames_recorded_ = 0;
  PixelRect drawn_area_;
  const FontAtlas* atlas_source_ = nullptr;
  std::uint64_t atlas_generation_ = 0;
  VkExtent2D atlas_extent_{};
  std::uint64_t atlas_updates_ = 0;  //!< copies of added glyphs into the texture (tests)
  GpuImage atlas_;
  VkDescriptorSet atlas_set_ = VK_NULL_HANDLE;
};

}  // namespace mallet::render
