#include "render/scene_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <initializer_list>
#include <span>
#include <vector>

#include "core/file_error.hpp"
#include "render/gltf_model.hpp"
#include "render/vk_error.hpp"
#include "shaders/overlay_frag.h"
#include "shaders/overlay_vert.h"
#include "shaders/gbuffer_frag.h"
#include "shaders/glow_frag.h"
#include "shaders/scene_frag.h"
#include "shaders/scene_vert.h"
#include "shaders/shadow_frag.h"
#include "shaders/shadow_vert.h"
#include "shaders/sphere_frag.h"

namespace mallet::render {
namespace {

constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
//! The cached background's light per pixel (gbuffer.frag): linear, unclamped.
constexpr VkFormat kLightFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
constexpr std::uint32_t kMaxModelSets = 256;
constexpr std::uint32_t kShadowTextures = 3;  //!< shadow.frag's: unshadowed, shadow share, depth

//! The key light (its direction: key_light_direction()).
constexpr float kLightTanRadius = 0.035f;  // a 2° disc: a soft but readable penumbra
constexpr float kLightIntensity = 2.6f;
constexpr float kAmbient = 0.55f;

struct FrameUniform {
  glm::mat4 view_proj;
  glm::vec4 eye, light_dir, sphere, light_color;
  glm::mat4 sphere_view_proj;
  glm::vec4 mallet;  //!< xyz: the head's centre; w: its radius (sphere.frag's, drawn or not its shadow)
};
struct DrawConstants {
  glm::mat4 model;
  glm::vec4 base_color;
  glm::vec4 params;
  glm::vec4 emissive;  //!< rgb: light the surface gives off (a lit bar), linear
};
static_assert(sizeof(DrawConstants) == 112, "push constants: 128 bytes guaranteed, 112 used");
struct ShadowConstants {
  glm::mat4 inverse_view_proj;
  glm::vec4 inverse_size;
  //! The two lit bars shaded on the screen: x the bar's id + 1 (0: none), yzw the light it
  //! gives off (its glow colour × kGlowStrength × its glow).
  glm::vec4 lit_a, lit_b;
  glm::vec4 shadow_rect;  //!< where the shadow can fall, pixels: x0, y0, x1, y1
};
static_assert(sizeof(ShadowConstants) <= 128, "push constants: 128 bytes guaranteed");

//! A lit bar with more triangles than this is lit on the screen from the cached bars (a pass
//! over its rectangle, whatever the triangles); one with fewer has its glow added over its
//! own triangles (the shipped bar has 12; measured at 1080p on lavapipe, the screen pass
//! over a shipped bar's rectangle cost more than redrawing it with scene.frag, and that
//! redraw cost 16 points of a core in the attract mode, which the added glow saves).
constexpr std::uint32_t kRedrawLitBarTriangles = 1000;

//! How brightly the bar `target` is lit this frame (the brighter of its lights); 0 when it
//! is not, and for what is not a bar (-1).
float glow_of(const FrameState& state, int target) {
  float glow = 0;
  if (target >= 0)
    for (const BarLight& l : state.bar_lights)
      if (l.target == target) glow = std::max(glow, l.glow);
  return glow;
}

//! A lit bar's light at glow 1 is its material's glow colour (Instance::glow_color, linear)
//! times this: bright enough to catch the eye on the lit bar (added to its shading), not so
//! bright that the bar's grain or metal is lost under it.
constexpr float kGlowStrength = 0.8f;

//! The light a lit bar gives off this frame (none when it is not lit).
glm::vec3 glow_light(const FrameState& state, const Instance& instance) {
  return instance.glow_color * (kGlowStrength * glow_of(state, instance.target));
}

template <std::size_t N>
vk::ShaderModule make_shader(VkDevice dev, const std::uint32_t (&code)[N]) {
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = sizeof(code);
  ci.pCode = code;
  VkShaderModule m;
  check(vkCreateShaderModule(dev, &ci, nullptr, &m), "creating a shader module");
  return vk::ShaderModule(dev, m);
}

std::span<const std::byte> bytes_of(const auto& vec) { return std::as_bytes(std::span(vec)); }

//! One interleaved vertex buffer at binding 0 with these attributes.
struct VertexInput {
  VkVertexInputBindingDescription binding;
  std::vector<VkVertexInputAttributeDescription> attributes;
  VkPipelineVertexInputStateCreateInfo info{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};

  VertexInput(std::uint32_t stride, std::vector<VkVertexInputAttributeDescription> attrs)
      : binding{0, stride, VK_VERTEX_INPUT_RATE_VERTEX}, attributes(std::move(attrs)) {
    info.vertexBindingDescriptionCount = 1;
    info.pVertexBindingDescriptions = &binding;
    info.vertexAttributeDescriptionCount = static_cast<std::uint32_t>(attributes.size());
    info.pVertexAttributeDescriptions = attributes.data();
  }
  VertexInput(const VertexInput&) = delete;
};

//! A depth attachment cleared to the far plane and kept (the cache's, read by later frames).
VkRenderingAttachmentInfo cleared_depth(VkImageView view) {
  VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  depth.imageView = view;
  depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  depth.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  depth.clearValue.depthStencil = {1.0f, 0};
  return depth;
}

//! Begins rendering into `colors` and `depth` (images of `extent`) over `area`, the
//! viewport the whole image and the scissor the area.
void begin_rendering(VkCommandBuffer cmd, std::span<const VkRenderingAttachmentInfo> colors,
                     const VkRenderingAttachmentInfo& depth, VkExtent2D extent, VkRect2D area) {
  VkRenderingInfo ri{VK_STRUCTURE_TYPE_RENDERING_INFO};
  ri.renderArea = area;
  ri.layerCount = 1;
  ri.colorAttachmentCount = static_cast<std::uint32_t>(colors.size());
  ri.pColorAttachments = colors.data();
  ri.pDepthAttachment = &depth;
  vkCmdBeginRendering(cmd, &ri);
  const VkViewport viewport{0, 0, static_cast<float>(extent.width), static_cast<float>(extent.height), 0, 1};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &area);
}

void begin_rendering(VkCommandBuffer cmd, std::span<const VkRenderingAttachmentInfo> colors,
                     const VkRenderingAttachmentInfo& depth, VkExtent2D extent) {
  begin_rendering(cmd, colors, depth, extent, {{0, 0}, extent});
}

}  // namespace

bool supports_samples(const Context& ctx, VkSampleCountFlagBits samples) {
  const VkPhysicalDeviceLimits& l = ctx.properties().limits;
  return (l.framebufferColorSampleCounts & l.framebufferDepthSampleCounts & samples) == samples;
}

VkSampleCountFlagBits recommended_samples(const Context& ctx) {
  if (ctx.properties().deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU) return VK_SAMPLE_COUNT_1_BIT;
  return supports_samples(ctx, VK_SAMPLE_COUNT_4_BIT) ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT;
}

void use_recommended_antialiasing(const Context& ctx, RenderSettings& settings) {
  settings.samples = recommended_samples(ctx);
  settings.background_samples =
      supports_samples(ctx, VK_SAMPLE_COUNT_4_BIT) ? VK_SAMPLE_COUNT_4_BIT : VK_SAMPLE_COUNT_1_BIT;
}

SceneRenderer::SceneRenderer(const Context& ctx, const Scene& scene, const std::filesystem::path& models_dir,
                             VkFormat color_format, RenderSettings settings, VkPipelineCache cache)
    : ctx_(ctx), scene_(scene), color_format_(color_format), settings_(settings) {
  VkDevice dev = ctx.device();
  if (settings.samples == VK_SAMPLE_COUNT_1_BIT && !supports_samples(ctx, settings.background_samples))
    settings_.background_samples = VK_SAMPLE_COUNT_1_BIT;  // a nicety, not a demand: drawn as the frames are
  if (!supports_samples(ctx, settings.samples)) {
    std::string offered;
    for (int n = 1; n <= 64; n *= 2)
      if (supports_samples(ctx, static_cast<VkSampleCountFlagBits>(n)))
        offered += (offered.empty() ? "" : ", ") + std::to_string(n);
    throw RenderError("antialiasing: " + std::to_string(static_cast<int>(settings.samples)) +
                      "x MSAA is not offered by " + ctx.device_name() + " (it offers: " + offered + ")");
  }
  view_proj_ = render::view_projection(scene);
  instruments_ = instrument_instances(scene);
  if (scene.background_srgb) {  // the scene's own background (sRGB) replaces the dark room
    for (std::size_t c = 0; c < 3; ++c)
      settings_.clear_color[c] = static_cast<float>(srgb_to_linear((*scene.background_srgb)[c]));
  }

  // Layouts, pool, sampler, the white texture untextured materials sample.
  VkDescriptorSetLayoutBinding ubo{0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1,
                                   VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
  VkDescriptorSetLayoutCreateInfo lci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  lci.bindingCount = 1;
  lci.pBindings = &ubo;
  VkDescriptorSetLayout raw_layout;
  check(vkCreateDescriptorSetLayout(dev, &lci, nullptr, &raw_layout), "creating a descriptor set layout");
  frame_layout_ = vk::DescriptorSetLayout(dev, raw_layout);
  VkDescriptorSetLayoutBinding tex{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT,
                                   nullptr};
  lci.pBindings = &tex;
  check(vkCreateDescriptorSetLayout(dev, &lci, nullptr, &raw_layout), "creating a descriptor set layout");
  image_layout_ = vk::DescriptorSetLayout(dev, raw_layout);
  std::array<VkDescriptorSetLayoutBinding, kShadowTextures> cached{};
  for (std::uint32_t b = 0; b < kShadowTextures; ++b)
    cached[b] = {b, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, VK_SHADER_STAGE_FRAGMENT_BIT, nullptr};
  lci.bindingCount = kShadowTextures;
  lci.pBindings = cached.data();
  check(vkCreateDescriptorSetLayout(dev, &lci, nullptr, &raw_layout), "creating a descriptor set layout");
  shadow_layout_ = vk::DescriptorSetLayout(dev, raw_layout);

  const std::array<VkDescriptorPoolSize, 2> sizes{
      {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kSlots},
       {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, kMaxModelSets + kShadowTextures}}};
  VkDescriptorPoolCreateInfo pci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pci.maxSets = kSlots + kMaxModelSets + 1;
  pci.poolSizeCount = static_cast<std::uint32_t>(sizes.size());
  pci.pPoolSizes = sizes.data();
  VkDescriptorPool raw_pool;
  check(vkCreateDescriptorPool(dev, &pci, nullptr, &raw_pool), "creating a descriptor pool");
  pool_ = vk::DescriptorPool(dev, raw_pool);

  VkSamplerCreateInfo sci{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  sci.magFilter = sci.minFilter = VK_FILTER_LINEAR;
  sci.mipmapMode = VK_SAMPLER_MIPMAP_MODE_NEAREST;
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_REPEAT;
  sci.maxLod = 0.0f;
  VkSampler raw_sampler;
  check(vkCreateSampler(dev, &sci, nullptr, &raw_sampler), "creating a sampler");
  sampler_ = vk::Sampler(dev, raw_sampler);
  // The glyph atlas never wraps: a glyph at its edge must not take in the opposite edge's.
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  check(vkCreateSampler(dev, &sci, nullptr, &raw_sampler), "creating a sampler");
  atlas_sampler_ = vk::Sampler(dev, raw_sampler);
  sci.magFilter = sci.minFilter = VK_FILTER_NEAREST;  // the cached light and depth: read texel by texel
  sci.addressModeU = sci.addressModeV = sci.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  check(vkCreateSampler(dev, &sci, nullptr, &raw_sampler), "creating a sampler");
  nearest_sampler_ = vk::Sampler(dev, raw_sampler);
  const std::array<std::uint8_t, 4> white{255, 255, 255, 255};
  white_ = make_texture(ctx, {1, 1}, VK_FORMAT_R8G8B8A8_SRGB, white, 4);

  for (Slot& slot : slots_) {
    slot.frame_uniform = make_host_buffer(ctx, sizeof(FrameUniform), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    slot.frame_set = allocate_set(frame_layout_.get());
    VkDescriptorBufferInfo bi{slot.frame_uniform.buffer.get(), 0, sizeof(FrameUniform)};
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = slot.frame_set;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    w.pBufferInfo = &bi;
    vkUpdateDescriptorSets(dev, 1, &w, 0, nullptr);
  }

  // Every model the scene draws, each loaded once.
  std::vector<std::string> names;
  for (const Instance& i : instruments_) names.push_back(i.model);
  names.push_back(mallet_instance(scene, {}).model);
  std::sort(names.begin(), names.end());
  names.erase(std::unique(names.begin(), names.end()), names.end());
  for (const std::string& name : names) {
    try {
      load_model(models_dir / name, name);
    } catch (const FileError& e) {  // say which setting chose the broken model
      const Scene::ModelRef* ref = scene.model_ref(name);
      if (!ref || ref->at.file.empty()) throw;
      throw FileError(ref->at, ref->key + " = \"" + name + "\": " + e.what());
    }
  }
  for (const Instance& i : instruments_) {
    const Box& b = models_.at(i.model).bounds;
    Box world;
    if (!b.empty())
      for (int c = 0; c < 8; ++c) world.add(glm::dvec3(i.transform * glm::vec4(glm::vec3(b.corner(c)), 1.0f)));
    instrument_boxes_.push_back(world);
    if (world.empty()) continue;
    instruments_box_.add(world.lo);
    instruments_box_.add(world.hi);
  }

  build_pipelines(cache);
}

SceneRenderer::~SceneRenderer() { vkDeviceWaitIdle(ctx_.device()); }

VkDescriptorSet SceneRenderer::allocate_set(VkDescriptorSetLayout layout) {
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = pool_.get();
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &layout;
  VkDescriptorSet set;
  check(vkAllocateDescriptorSets(ctx_.device(), &ai, &set), "allocating a descriptor set (too many materials?)");
  return set;
}

void SceneRenderer::write_image_set(VkDescriptorSet set, VkImageView view, VkSampler sampler) {
  VkDescriptorImageInfo ii{sampler != VK_NULL_HANDLE ? sampler : sampler_.get(), view,
                           VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
  VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
  w.dstSet = set;
  w.descriptorCount = 1;
  w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
  w.pImageInfo = &ii;
  vkUpdateDescriptorSets(ctx_.device(), 1, &w, 0, nullptr);
}

void SceneRenderer::load_model(const std::filesystem::path& file, const std::string& name) {
  const Model model = load_gltf(file);
  GpuModel gpu;
  std::vector<Vertex> vertices;
  std::vector<std::uint32_t> indices;
  for (const Primitive& p : model.primitives) {
    GpuPrimitive gp;
    gp.first_index = static_cast<std::uint32_t>(indices.size());
    gp.index_count = static_cast<std::uint32_t>(p.indices.size());
    gp.vertex_offset = static_cast<std::int32_t>(vertices.size());
    gp.material = p.material;
    vertices.insert(vertices.end(), p.vertices.begin(), p.vertices.end());
    for (const Vertex& v : p.vertices) gpu.bounds.add({v.position[0], v.position[1], v.position[2]});
    indices.insert(indices.end(), p.indices.begin(), p.indices.end());
    gpu.primitives.push_back(gp);
  }
  gpu.vertices = make_host_buffer(ctx_, bytes_of(vertices), VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  gpu.indices = make_host_buffer(ctx_, bytes_of(indices), VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  for (const TextureImage& t : model.textures)
    gpu.textures.push_back(make_texture(ctx_, {static_cast<std::uint32_t>(t.width), static_cast<std::uint32_t>(t.height)},
                                        VK_FORMAT_R8G8B8A8_SRGB, t.rgba, 4));
  std::vector<PbrMaterial> materials = model.materials;
  materials.push_back(PbrMaterial{});  // glTF's default material, for primitives without one
  for (GpuPrimitive& gp : gpu.primitives)
    if (gp.material < 0) gp.material = static_cast<int>(materials.size()) - 1;
  for (const PbrMaterial& m : materials) {
    GpuMaterial g;
    g.base_color = m.base_color;
    g.metallic = m.metallic;
    g.roughness = m.roughness;
    g.textured = m.base_color_texture >= 0;
    g.set = allocate_set(image_layout_.get());
    write_image_set(g.set, g.textured ? gpu.textures.at(m.base_color_texture).view.get() : white_.view.get());
    gpu.materials.push_back(g);
  }
  models_.emplace(name, std::move(gpu));
}

void SceneRenderer::build_pipelines(VkPipelineCache cache) {
  VkDevice dev = ctx_.device();
  auto layout_of = [dev](std::initializer_list<VkDescriptorSetLayout> sets, VkPushConstantRange push,
                         const char* what) {
    VkPipelineLayoutCreateInfo ci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
    ci.setLayoutCount = static_cast<std::uint32_t>(sets.size());
    ci.pSetLayouts = sets.begin();
    ci.pushConstantRangeCount = 1;
    ci.pPushConstantRanges = &push;
    VkPipelineLayout raw;
    check(vkCreatePipelineLayout(dev, &ci, nullptr, &raw), what);
    return vk::PipelineLayout(dev, raw);
  };
  // Scene pipeline: set 0 the frame, set 1 the material's texture; push constants per draw.
  scene_pipeline_layout_ =
      layout_of({frame_layout_.get(), image_layout_.get()},
                {VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(DrawConstants)},
                "creating the scene pipeline layout");
  overlay_pipeline_layout_ = layout_of({image_layout_.get()}, {VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(float) * 2},
                                       "creating the overlay pipeline layout");
  // The shadow on the screen: set 0 the frame, set 1 the cached light and depth.
  shadow_pipeline_layout_ =
      layout_of({frame_layout_.get(), shadow_layout_.get()},
                {VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(ShadowConstants)}, "creating the shadow pipeline layout");

  // How a pipeline uses depth: the overlay not at all; the whole scene tests and writes
  // it; drawing over the cached background only tests against it (it stays the cache).
  enum class Depth { none, test_and_write, test_only };
  // How a pipeline's colour meets what is drawn: replaces it, straight alpha over it (the
  // overlay), or added to it (a lit bar's glow).
  enum class Blend { opaque, alpha_over, add };
  auto build = [&](VkShaderModule vs, VkShaderModule fs, const VkPipelineVertexInputStateCreateInfo& input,
                   Depth depth, Blend blend, VkPipelineLayout layout, const char* what,
                   VkSampleCountFlagBits samples, std::vector<VkFormat> formats = {}) {
    if (formats.empty()) formats.push_back(color_format_);
    std::array<VkPipelineShaderStageCreateInfo, 2> stages{};
    stages[0] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_VERTEX_BIT, vs,
                 "main", nullptr};
    stages[1] = {VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO, nullptr, 0, VK_SHADER_STAGE_FRAGMENT_BIT, fs,
                 "main", nullptr};
    VkPipelineInputAssemblyStateCreateInfo ia{VK_STRUCTURE_TYPE_PIPELINE_INPUT_ASSEMBLY_STATE_CREATE_INFO};
    ia.topology = VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
    VkPipelineViewportStateCreateInfo vp{VK_STRUCTURE_TYPE_PIPELINE_VIEWPORT_STATE_CREATE_INFO};
    vp.viewportCount = vp.scissorCount = 1;
    VkPipelineRasterizationStateCreateInfo rs{VK_STRUCTURE_TYPE_PIPELINE_RASTERIZATION_STATE_CREATE_INFO};
    rs.polygonMode = VK_POLYGON_MODE_FILL;
    // The models are closed and wind their front faces counter-clockwise (glTF). Vulkan's
    // framebuffer y points down and so does our projection's, so the two flips cancel and
    // they stay counter-clockwise (the goldens are unchanged with culling on; with the
    // opposite winding they break). Culling back faces halves what lavapipe rasterises.
    // The overlay is drawn as given.
    rs.cullMode = depth != Depth::none ? VK_CULL_MODE_BACK_BIT : VK_CULL_MODE_NONE;
    rs.frontFace = VK_FRONT_FACE_COUNTER_CLOCKWISE;
    rs.lineWidth = 1.0f;
    VkPipelineMultisampleStateCreateInfo ms{VK_STRUCTURE_TYPE_PIPELINE_MULTISAMPLE_STATE_CREATE_INFO};
    ms.rasterizationSamples = samples;
    VkPipelineDepthStencilStateCreateInfo ds{VK_STRUCTURE_TYPE_PIPELINE_DEPTH_STENCIL_STATE_CREATE_INFO};
    ds.depthTestEnable = depth != Depth::none ? VK_TRUE : VK_FALSE;
    ds.depthWriteEnable = depth == Depth::test_and_write ? VK_TRUE : VK_FALSE;
    // Redrawn instruments meet their own cached depth: equal passes, what they hid fails.
    ds.depthCompareOp = depth == Depth::test_only ? VK_COMPARE_OP_LESS_OR_EQUAL : VK_COMPARE_OP_LESS;
    constexpr VkColorComponentFlags kRgba =
        VK_COLOR_COMPONENT_R_BIT | VK_COLOR_COMPONENT_G_BIT | VK_COLOR_COMPONENT_B_BIT | VK_COLOR_COMPONENT_A_BIT;
    constexpr VkPipelineColorBlendAttachmentState kOpaque{.colorWriteMask = kRgba};
    // Straight alpha over what is drawn: colour = a·src + (1 − a)·dst.
    constexpr VkPipelineColorBlendAttachmentState kAlphaOver{
        .blendEnable = VK_TRUE, .srcColorBlendFactor = VK_BLEND_FACTOR_SRC_ALPHA,
        .dstColorBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA, .colorBlendOp = VK_BLEND_OP_ADD,
        .srcAlphaBlendFactor = VK_BLEND_FACTOR_ONE, .dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA,
        .alphaBlendOp = VK_BLEND_OP_ADD, .colorWriteMask = kRgba};
    // Light added, the alpha kept: colour = src + dst.
    constexpr VkPipelineColorBlendAttachmentState kAdd{
        .blendEnable = VK_TRUE, .srcColorBlendFactor = VK_BLEND_FACTOR_ONE, .dstColorBlendFactor = VK_BLEND_FACTOR_ONE,
        .colorBlendOp = VK_BLEND_OP_ADD, .srcAlphaBlendFactor = VK_BLEND_FACTOR_ZERO,
        .dstAlphaBlendFactor = VK_BLEND_FACTOR_ONE, .alphaBlendOp = VK_BLEND_OP_ADD, .colorWriteMask = kRgba};
    const std::vector<VkPipelineColorBlendAttachmentState> atts(
        formats.size(), blend == Blend::alpha_over ? kAlphaOver : blend == Blend::add ? kAdd : kOpaque);
    VkPipelineColorBlendStateCreateInfo cb{VK_STRUCTURE_TYPE_PIPELINE_COLOR_BLEND_STATE_CREATE_INFO};
    cb.attachmentCount = static_cast<std::uint32_t>(atts.size());
    cb.pAttachments = atts.data();
    const std::array<VkDynamicState, 2> dyn{VK_DYNAMIC_STATE_VIEWPORT, VK_DYNAMIC_STATE_SCISSOR};
    VkPipelineDynamicStateCreateInfo dy{VK_STRUCTURE_TYPE_PIPELINE_DYNAMIC_STATE_CREATE_INFO};
    dy.dynamicStateCount = static_cast<std::uint32_t>(dyn.size());
    dy.pDynamicStates = dyn.data();
    VkPipelineRenderingCreateInfo rendering{VK_STRUCTURE_TYPE_PIPELINE_RENDERING_CREATE_INFO};
    rendering.colorAttachmentCount = static_cast<std::uint32_t>(formats.size());
    rendering.pColorAttachmentFormats = formats.data();
    rendering.depthAttachmentFormat = kDepthFormat;
    VkGraphicsPipelineCreateInfo ci{VK_STRUCTURE_TYPE_GRAPHICS_PIPELINE_CREATE_INFO};
    ci.pNext = &rendering;
    ci.stageCount = 2;
    ci.pStages = stages.data();
    ci.pVertexInputState = &input;
    ci.pInputAssemblyState = &ia;
    ci.pViewportState = &vp;
    ci.pRasterizationState = &rs;
    ci.pMultisampleState = &ms;
    ci.pDepthStencilState = &ds;
    ci.pColorBlendState = &cb;
    ci.pDynamicState = &dy;
    ci.layout = layout;
    VkPipeline raw;
    check(vkCreateGraphicsPipelines(dev, cache, 1, &ci, nullptr, &raw), what);
    return vk::Pipeline(dev, raw);
  };

  {
    vk::ShaderModule vs = make_shader(dev, scene_vert_spv), fs = make_shader(dev, scene_frag_spv);
    const VertexInput input(sizeof(Vertex), {{0, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, position)},
                                             {1, 0, VK_FORMAT_R32G32B32_SFLOAT, offsetof(Vertex, normal)},
                                             {2, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(Vertex, uv)}});
    scene_pipeline_ = build(vs.get(), fs.get(), input.info, Depth::test_and_write, Blend::opaque,
                            scene_pipeline_layout_.get(), "creating the scene pipeline", settings_.samples);
    over_background_pipeline_ = build(vs.get(), fs.get(), input.info, Depth::test_only, Blend::opaque,
                                      scene_pipeline_layout_.get(), "creating the over-background pipeline",
                                      settings_.samples);
    if (background_samples() != settings_.samples)
      background_pipeline_ = build(vs.get(), fs.get(), input.info, Depth::test_and_write, Blend::opaque,
                                   scene_pipeline_layout_.get(), "creating the background pipeline",
                                   background_samples());
    // The head: depth-tested at the exact sphere's depth (sphere.frag writes it), never
    // writing it, blended over what is drawn by its coverage (its antialiased edge).
    vk::ShaderModule sphere = make_shader(dev, sphere_frag_spv);
    sphere_pipeline_ = build(vs.get(), sphere.get(), input.info, Depth::test_only, Blend::alpha_over,
                             scene_pipeline_layout_.get(), "creating the mallet head's pipeline", settings_.samples);
    vk::ShaderModule light = make_shader(dev, gbuffer_frag_spv), glow = make_shader(dev, glow_frag_spv);
    if (screen_space_shadow()) {
      light_pipeline_ = build(vs.get(), light.get(), input.info, Depth::test_and_write, Blend::opaque,
                              scene_pipeline_layout_.get(), "creating the cached light's pipeline",
                              VK_SAMPLE_COUNT_1_BIT, {kLightFormat, kLightFormat});
      glow_pipeline_ = build(vs.get(), glow.get(), input.info, Depth::test_only, Blend::add,
                             scene_pipeline_layout_.get(), "creating the glow's pipeline", settings_.samples);
    }
  }
  {
    vk::ShaderModule vs = make_shader(dev, shadow_vert_spv), fs = make_shader(dev, shadow_frag_spv);
    VkPipelineVertexInputStateCreateInfo none{VK_STRUCTURE_TYPE_PIPELINE_VERTEX_INPUT_STATE_CREATE_INFO};
    if (screen_space_shadow())
      shadow_pipeline_ = build(vs.get(), fs.get(), none, Depth::none, Blend::opaque, shadow_pipeline_layout_.get(),
                               "creating the shadow pipeline", settings_.samples);
  }
  {
    vk::ShaderModule vs = make_shader(dev, overlay_vert_spv), fs = make_shader(dev, overlay_frag_spv);
    const VertexInput input(sizeof(OverlayVertex),
                            {{0, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(OverlayVertex, x)},
                             {1, 0, VK_FORMAT_R32G32_SFLOAT, offsetof(OverlayVertex, u)},
                             {2, 0, VK_FORMAT_R32G32B32A32_SFLOAT, offsetof(OverlayVertex, color)}});
    overlay_pipeline_ = build(vs.get(), fs.get(), input.info, Depth::none, Blend::alpha_over, overlay_pipeline_layout_.get(),
                              "creating the overlay pipeline", settings_.samples);
  }
}

void SceneRenderer::ensure_attachments(VkExtent2D extent) {
  if (extent.width == attachment_extent_.width && extent.height == attachment_extent_.height) return;
  vkDeviceWaitIdle(ctx_.device());  // resizes are rare; the old attachments may be in use
  // The scene framed for the image's proportions: nothing stretched, all of it in view.
  view_proj_ = render::view_projection(scene_, static_cast<double>(extent.width) / extent.height);
  instrument_rects_.clear();
  for (const Box& b : instrument_boxes_)
    instrument_rects_.push_back(
        screen_rect(view_proj_, static_cast<int>(extent.width), static_cast<int>(extent.height), b));
  depth_ = make_image(ctx_, extent, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, settings_.samples,
                      VK_IMAGE_ASPECT_DEPTH_BIT);
  msaa_color_ = {};
  if (settings_.samples != VK_SAMPLE_COUNT_1_BIT)
    msaa_color_ = make_image(ctx_, extent, color_format_,
                             VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT, settings_.samples,
                             VK_IMAGE_ASPECT_COLOR_BIT);
  background_color_ = {};
  background_depth_ = {};
  background_msaa_color_ = {};
  background_msaa_depth_ = {};
  background_scratch_slot_.reset();
  if (settings_.background_cache) {
    background_color_ = make_image(ctx_, extent, color_format_,
                                   VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT,
                                   settings_.samples, VK_IMAGE_ASPECT_COLOR_BIT);
    background_depth_ = make_image(ctx_, extent, kDepthFormat, VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT,
                                   settings_.samples, VK_IMAGE_ASPECT_DEPTH_BIT);
  }
  light_unshadowed_ = {};
  light_share_ = {};
  light_depth_ = {};
  if (screen_space_shadow()) {
    // The shadow's inputs, read by shadow.frag: the light per pixel and where it lies.
    constexpr VkImageUsageFlags cached = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
    light_unshadowed_ =
        make_image(ctx_, extent, kLightFormat, cached, VK_SAMPLE_COUNT_1_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
    light_share_ = make_image(ctx_, extent, kLightFormat, cached, VK_SAMPLE_COUNT_1_BIT, VK_IMAGE_ASPECT_COLOR_BIT);
    light_depth_ = make_image(ctx_, extent, kDepthFormat,
                              VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT,
                              VK_SAMPLE_COUNT_1_BIT, VK_IMAGE_ASPECT_DEPTH_BIT);
    if (shadow_set_ == VK_NULL_HANDLE) shadow_set_ = allocate_set(shadow_layout_.get());
    std::array<VkDescriptorImageInfo, kShadowTextures> images{};
    const std::array<VkImageView, kShadowTextures> views{light_unshadowed_.view.get(), light_share_.view.get(),
                                                         light_depth_.view.get()};
    std::array<VkWriteDescriptorSet, kShadowTextures> writes{};
    for (std::uint32_t b = 0; b < kShadowTextures; ++b) {
      images[b] = {nearest_sampler_.get(), views[b], VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
      writes[b] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      writes[b].dstSet = shadow_set_;
      writes[b].dstBinding = b;
      writes[b].descriptorCount = 1;
      writes[b].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
      writes[b].pImageInfo = &images[b];
    }
    vkUpdateDescriptorSets(ctx_.device(), kShadowTextures, writes.data(), 0, nullptr);
  }
  background_ready_ = false;
  attachment_extent_ = extent;
}

void SceneRenderer::ensure_atlas(VkCommandBuffer cmd, const FontAtlas& atlas, Slot& slot) {
  // The atlas fills as text is first shown (render/font_atlas.hpp): the GPU's copy follows it
  // whenever it changed, which after the first frames of a language is seldom.
  if (atlas_source_ == &atlas && atlas_generation_ == atlas.generation()) return;
  const VkExtent2D extent{static_cast<std::uint32_t>(atlas.width()), static_cast<std::uint32_t>(atlas.height())};
  if (atlas_source_ != &atlas || atlas_extent_.width != extent.width || atlas_extent_.height != extent.height) {
    // Another font (another screen size): its own texture, made once, with nothing in flight.
    vkDeviceWaitIdle(ctx_.device());
    atlas_ = make_texture(ctx_, extent, VK_FORMAT_R8_UNORM, atlas.coverage(), 1);
    if (atlas_set_ == VK_NULL_HANDLE) atlas_set_ = allocate_set(image_layout_.get());
    write_image_set(atlas_set_, atlas_.view.get(), atlas_sampler_.get());
    atlas_source_ = &atlas;
    atlas_extent_ = extent;
    atlas_generation_ = atlas.generation();
    return;
  }
  // Glyphs added: copied into the texture the frames already sample, by this frame's own
  // commands, after every earlier frame's reads (the barrier's first scope) and before its own
  // text. The texture and its descriptor stay as they are: a texture freed or a descriptor
  // rewritten while a frame may still read it is what crashed lavapipe's rasterizer threads in
  // the VM test (a read of freed memory, as new text first showed).
  const std::span<const std::uint8_t> texels = atlas.coverage();
  if (slot.atlas_staging.size < texels.size())
    slot.atlas_staging = make_host_buffer(ctx_, texels.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  std::memcpy(slot.atlas_staging.mapped, texels.data(), texels.size());
  record_texture_upload(cmd, slot.atlas_staging.buffer.get(), atlas_.image.get(), extent,
                        VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                        VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  atlas_generation_ = atlas.generation();
  ++atlas_updates_;
}

std::uint32_t SceneRenderer::triangles_of(const Instance& instance) const {
  std::uint32_t n = 0;
  for (const GpuPrimitive& p : models_.at(instance.model).primitives) n += p.index_count / 3;
  return n;
}

PixelRect SceneRenderer::shadow_rect(const FrameState& state) const {
  if (!settings_.shadow || !state.draw_mallet) return {};
  return shadow_bounds(view_proj_, static_cast<int>(attachment_extent_.width),
                       static_cast<int>(attachment_extent_.height),
                       {{state.mallet_centre.x, state.mallet_centre.y, 0.0}, scene_.mallet_radius_m,
                        key_light_direction(scene_), kLightTanRadius},
                       instruments_box_);
}

FrameLook SceneRenderer::look_of(const FrameState& state, VkExtent2D extent) const {
  FrameLook look;
  look.width = static_cast<int>(extent.width);
  look.height = static_cast<int>(extent.height);
  look.instruments = state.draw_instruments;
  // Another size changes everything; the rectangles are those of the attachments' size.
  if (extent.width != attachment_extent_.width || extent.height != attachment_extent_.height) return look;
  look.mallet = state.draw_mallet;
  if (state.draw_mallet) {
    look.mallet_centre = state.mallet_centre;
    const glm::dvec3 c{state.mallet_centre.x, state.mallet_centre.y, 0.0};
    look.mallet_px = project_to_screen(view_proj_, c) * glm::dvec2(look.width, look.height);
    // The head as it is drawn: its hull's box, placed and seen as record() draws it.
    const Instance head = mallet_hull(scene_, state.mallet_centre);
    const Box& model = models_.at(head.model).bounds;
    Box placed;
    for (int i = 0; i < 8; ++i) placed.add(glm::dvec3(glm::dmat4(head.transform) * glm::dvec4(model.corner(i), 1.0)));
    const glm::mat4 seen = sphere_view_projection(scene_, static_cast<double>(extent.width) / extent.height,
                                                  state.mallet_centre);
    look.mallet_rect = bounding(screen_rect(seen, look.width, look.height, placed), shadow_rect(state));
  }
  look.lights = state.bar_lights;
  for (std::size_t l = 0; l < look.lights.size(); ++l)
    for (std::size_t k = 0; k < instruments_.size(); ++k)
      if (look.lights[l].target >= 0 && instruments_[k].target == look.lights[l].target)
        look.light_rects[l] = bounding(look.light_rects[l], instrument_rects_[k]);
  if (state.overlay) {
    look.overlay_vertices = state.overlay->vertices();
    look.overlay_indices = state.overlay->indices();
    look.overlay_atlas = &state.overlay->atlas();
    look.overlay_atlas_generation = state.overlay->atlas().generation();
  }
  return look;
}

bool SceneRenderer::changes(const FrameState& state, VkExtent2D extent) const {
  return !background_ready_ || damage_.changes(look_of(state, extent));
}

std::size_t SceneRenderer::triangle_count() const {
  std::size_t n = 0;
  auto count = [&](const std::string& name) {
    for (const GpuPrimitive& p : models_.at(name).primitives) n += p.index_count / 3;
  };
  for (const Instance& i : instruments_) count(i.model);
  count(mallet_instance(scene_, {}).model);
  return n;
}

void SceneRenderer::draw_instance(VkCommandBuffer cmd, const Instance& instance, Shadow shadow, glm::vec3 emissive) {
  const GpuModel& model = models_.at(instance.model);
  const VkDeviceSize offset = 0;
  VkBuffer vb = model.vertices.buffer.get();
  vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
  vkCmdBindIndexBuffer(cmd, model.indices.buffer.get(), 0, VK_INDEX_TYPE_UINT32);
  for (const GpuPrimitive& p : model.primitives) {
    const GpuMaterial& m = model.materials.at(p.material);
    DrawConstants dc{instance.transform,
                     {m.base_color[0], m.base_color[1], m.base_color[2], m.base_color[3]},
                     {m.metallic, m.roughness, static_cast<float>(shadow), m.textured ? 1.0f : 0.0f},
                     // w: the bar's id + 1 (0: not a bar), which the cached light keeps per pixel
                     glm::vec4(emissive, static_cast<float>(instance.target + 1))};
    vkCmdPushConstants(cmd, scene_pipeline_layout_.get(), VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT,
                       0, sizeof(dc), &dc);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, scene_pipeline_layout_.get(), 1, 1, &m.set, 0,
                            nullptr);
    vkCmdDrawIndexed(cmd, p.index_count, 1, p.first_index, p.vertex_offset, 0);
  }
}

void SceneRenderer::draw_overlay(VkCommandBuffer cmd, const Overlay& overlay, Slot& slot, VkExtent2D extent) {
  if (overlay.indices().empty()) return;
  // Its atlas's texture is up to date: record() copied the new glyphs before any drawing.
  const auto vbytes = bytes_of(overlay.vertices());
  const auto ibytes = bytes_of(overlay.indices());
  if (slot.overlay_vertices.size < vbytes.size())
    slot.overlay_vertices = make_host_buffer(ctx_, std::max<VkDeviceSize>(vbytes.size() * 2, 64 * 1024),
                                             VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  if (slot.overlay_indices.size < ibytes.size())
    slot.overlay_indices = make_host_buffer(ctx_, std::max<VkDeviceSize>(ibytes.size() * 2, 32 * 1024),
                                            VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  std::memcpy(slot.overlay_vertices.mapped, vbytes.data(), vbytes.size());
  std::memcpy(slot.overlay_indices.mapped, ibytes.data(), ibytes.size());
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, overlay_pipeline_.get());
  const float size[2] = {static_cast<float>(extent.width), static_cast<float>(extent.height)};
  vkCmdPushConstants(cmd, overlay_pipeline_layout_.get(), VK_SHADER_STAGE_VERTEX_BIT, 0, sizeof(size), size);
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, overlay_pipeline_layout_.get(), 0, 1, &atlas_set_, 0,
                          nullptr);
  const VkDeviceSize offset = 0;
  VkBuffer vb = slot.overlay_vertices.buffer.get();
  vkCmdBindVertexBuffers(cmd, 0, 1, &vb, &offset);
  vkCmdBindIndexBuffer(cmd, slot.overlay_indices.buffer.get(), 0, VK_INDEX_TYPE_UINT32);
  vkCmdDrawIndexed(cmd, static_cast<std::uint32_t>(overlay.indices().size()), 1, 0, 0, 0);
}

void SceneRenderer::record_background(VkCommandBuffer cmd, const Slot& slot, std::uint32_t slot_index) {
  const bool resolve = background_samples() != settings_.samples;
  if (resolve) {
    // Drawn with more samples than the frames, then resolved into the 1-sample cache; these
    // images are freed once this frame is done (record(), the next time this slot comes).
    background_msaa_color_ = make_image(ctx_, attachment_extent_, color_format_, VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT,
                                        background_samples(), VK_IMAGE_ASPECT_COLOR_BIT);
    background_msaa_depth_ = make_image(ctx_, attachment_extent_, kDepthFormat,
                                        VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, background_samples(),
                                        VK_IMAGE_ASPECT_DEPTH_BIT);
    background_scratch_slot_ = slot_index;
  }
  const VkPipelineStageFlags2 color_stage = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
  const VkPipelineStageFlags2 depth_stages =
      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
  // New images (made with the size, or just above): nothing to keep, nothing to wait for.
  auto to_attachments = [&](const GpuImage& c, const GpuImage& d) {
    transition(cmd, c.image.get(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, color_stage, VK_ACCESS_2_NONE, color_stage,
               VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
    transition(cmd, d.image.get(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, depth_stages, VK_ACCESS_2_NONE, depth_stages,
               VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
  };
  to_attachments(background_color_, background_depth_);
  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = background_color_.view.get();
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  color.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  color.clearValue.color = {{settings_.clear_color[0], settings_.clear_color[1], settings_.clear_color[2], 1.0f}};
  VkRenderingAttachmentInfo depth = cleared_depth(background_depth_.view.get());
  if (resolve) {  // drawn multisampled, resolved into the cache: colour averaged, depth of sample 0
    to_attachments(background_msaa_color_, background_msaa_depth_);
    color.imageView = background_msaa_color_.view.get();
    color.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    color.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
    color.resolveImageView = background_color_.view.get();
    color.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    depth.imageView = background_msaa_depth_.view.get();
    depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depth.resolveMode = VK_RESOLVE_MODE_SAMPLE_ZERO_BIT;  // every device offers it
    depth.resolveImageView = background_depth_.view.get();
    depth.resolveImageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
  }
  begin_rendering(cmd, {&color, 1}, depth, attachment_extent_);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                    resolve ? background_pipeline_.get() : scene_pipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, scene_pipeline_layout_.get(), 0, 1, &slot.frame_set, 0,
                          nullptr);
  // Unshadowed: wherever the sphere darkens them, the frame shades them again (shadow.frag).
  for (const Instance& i : instruments_) draw_instance(cmd, i, Shadow::none);
  vkCmdEndRendering(cmd);

  // Every later frame copies the colour and tests against the depth; neither changes again.
  transition(cmd, background_color_.image.get(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
             VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, color_stage, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
             VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
  transition(cmd, background_depth_.image.get(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
             VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL, depth_stages, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
             depth_stages, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
  if (screen_space_shadow()) record_cached_light(cmd, slot);
}

void SceneRenderer::record_cached_light(VkCommandBuffer cmd, const Slot& slot) {
  const VkPipelineStageFlags2 color_stage = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
  const VkPipelineStageFlags2 depth_stages =
      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
  // The same instruments' light per pixel, at one sample a pixel, and their depth: what the
  // shadow takes from each pixel, shaded on the screen by every later frame.
  for (const GpuImage* c : {&light_unshadowed_, &light_share_})
    transition(cmd, c->image.get(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, color_stage, VK_ACCESS_2_NONE, color_stage,
               VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT);
  transition(cmd, light_depth_.image.get(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
             VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL, depth_stages, VK_ACCESS_2_NONE, depth_stages,
             VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
  std::array<VkRenderingAttachmentInfo, 2> lights{};
  for (std::size_t k = 0; k < lights.size(); ++k) {
    lights[k] = {VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    lights[k].imageView = (k == 0 ? light_unshadowed_ : light_share_).view.get();
    lights[k].imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    lights[k].loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    lights[k].storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    lights[k].clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
  }
  begin_rendering(cmd, lights, cleared_depth(light_depth_.view.get()), attachment_extent_);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, light_pipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, scene_pipeline_layout_.get(), 0, 1, &slot.frame_set, 0,
                          nullptr);
  for (const Instance& i : instruments_) draw_instance(cmd, i, Shadow::none);
  vkCmdEndRendering(cmd);
  const VkPipelineStageFlags2 fragment = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
  for (const GpuImage* c : {&light_unshadowed_, &light_share_})
    transition(cmd, c->image.get(), VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, color_stage, VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, fragment,
               VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  transition(cmd, light_depth_.image.get(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
             VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, depth_stages, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
             fragment, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
}

void SceneRenderer::record(VkCommandBuffer cmd, const FrameTarget& target, const FrameState& requested,
                           std::uint32_t slot_index) {
  const VkExtent2D extent = target.extent;
  ensure_attachments(extent);
  Slot& slot = slots_.at(slot_index);
  // Before any drawing: the atlas's new glyphs are copied outside the frame's rendering.
  if (requested.overlay && !requested.overlay->indices().empty()) ensure_atlas(cmd, requested.overlay->atlas(), slot);
  if (background_scratch_slot_ == slot_index) {  // the frame that drew the background is done
    background_msaa_color_ = {};
    background_msaa_depth_ = {};
    background_scratch_slot_.reset();
  }

  const bool msaa = settings_.samples != VK_SAMPLE_COUNT_1_BIT;
  // Over the cached background when there is one and the frame can receive its copy.
  const bool over_background =
      settings_.background_cache && requested.draw_instruments && (msaa || target.copy_destination);
  if (over_background && !background_ready_) {
    record_background(cmd, slot, slot_index);
    background_ready_ = true;
    ++background_builds_;
    damage_.forget();  // every image was drawn over another background
  }

  // What to draw: on a kept image (single-sampled, over the background) only what changed
  // since the frame it holds; else all of it.
  const std::uint64_t frame = frames_recorded_++;
  int age = 0;
  if (const auto held = drawn_into_.find(target.image);
      target.kept && over_background && !msaa && held != drawn_into_.end() && frame - held->second <= FrameDamage::kHistory)
    age = static_cast<int>(frame - held->second);
  if (drawn_into_.size() > 16) drawn_into_.clear();  // images of swapchains long gone
  drawn_into_[target.image] = frame;
  PixelRect area = damage_.commit(look_of(requested, extent), age);
  // Nothing changed (a window asked to show its picture again): one pixel drawn as before,
  // so that the frame's commands keep their shape.
  if (area.empty()) area = {0, 0, 1, 1};
  // What the frame shows: on a kept image the head and the glows that changed less than a
  // step stay as the image has them (FrameDamage::commit), so that no pixel of them differs
  // from the rest of their drawing.
  FrameState state = requested;
  const FrameLook& drawn = damage_.drawn();
  if (drawn.mallet) state.mallet_centre = drawn.mallet_centre;
  state.bar_lights = drawn.lights;

  FrameUniform u;
  u.view_proj = view_proj_;
  u.sphere_view_proj =
      sphere_view_projection(scene_, static_cast<double>(extent.width) / extent.height, state.mallet_centre);
  u.eye = glm::vec4(eye_position(scene_), 1.0f);
  u.light_dir = glm::vec4(glm::vec3(key_light_direction(scene_)), kLightTanRadius);
  const bool caster = settings_.shadow && state.draw_mallet;
  u.sphere = glm::vec4(static_cast<float>(state.mallet_centre.x), static_cast<float>(state.mallet_centre.y), 0.0f,
                       caster ? static_cast<float>(scene_.mallet_radius_m) : 0.0f);
  u.light_color = glm::vec4(glm::vec3(kLightIntensity), kAmbient);
  u.mallet = glm::vec4(static_cast<float>(state.mallet_centre.x), static_cast<float>(state.mallet_centre.y), 0.0f,
                       static_cast<float>(scene_.mallet_radius_m));
  std::memcpy(slot.frame_uniform.mapped, &u, sizeof(u));

  drawn_area_ = area;
  const bool partial = age > 0;
  const VkRect2D area_rect{{area.x0, area.y0},
                           {static_cast<std::uint32_t>(area.x1 - area.x0), static_cast<std::uint32_t>(area.y1 - area.y0)}};

  const VkPipelineStageFlags2 color_stage = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
  const VkAccessFlags2 color_write = VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
  const VkImage attachment = msaa ? msaa_color_.image.get() : target.image;
  if (over_background) {
    // A kept image keeps its pixels outside the area: from its layout, not from UNDEFINED.
    transition(cmd, attachment, VK_IMAGE_ASPECT_COLOR_BIT, partial ? target.kept_layout : VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kTargetFirstUse, VK_ACCESS_2_NONE, VK_PIPELINE_STAGE_2_COPY_BIT,
               VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkImageCopy region{};
    region.srcSubresource = region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.srcOffset = region.dstOffset = {area.x0, area.y0, 0};
    region.extent = {area_rect.extent.width, area_rect.extent.height, 1};
    vkCmdCopyImage(cmd, background_color_.image.get(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, attachment,
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    transition(cmd, attachment, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
               VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
               color_stage, VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | color_write);
  } else {
    transition(cmd, attachment, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, kTargetFirstUse, VK_ACCESS_2_NONE, color_stage, color_write);
    transition(cmd, depth_.image.get(), VK_IMAGE_ASPECT_DEPTH_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL,
               VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
               VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
               VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
               VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT);
  }
  if (msaa)  // the resolve's destination
    transition(cmd, target.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_UNDEFINED,
               VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, kTargetFirstUse, VK_ACCESS_2_NONE, color_stage, color_write);

  VkRenderingAttachmentInfo color{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  color.imageView = msaa ? msaa_color_.view.get() : target.view;
  color.imageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  color.loadOp = over_background ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
  color.storeOp = msaa ? VK_ATTACHMENT_STORE_OP_DONT_CARE : VK_ATTACHMENT_STORE_OP_STORE;
  color.clearValue.color = {{settings_.clear_color[0], settings_.clear_color[1], settings_.clear_color[2], 1.0f}};
  if (msaa) {
    color.resolveMode = VK_RESOLVE_MODE_AVERAGE_BIT;
    color.resolveImageView = target.view;
    color.resolveImageLayout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
  }
  VkRenderingAttachmentInfo depth{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  if (over_background) {  // read only: it stays the cache
    depth.imageView = background_depth_.view.get();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_LOAD;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_NONE;
  } else {
    depth.imageView = depth_.view.get();
    depth.imageLayout = VK_IMAGE_LAYOUT_DEPTH_ATTACHMENT_OPTIMAL;
    depth.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth.storeOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depth.clearValue.depthStencil = {1.0f, 0};
  }
  begin_rendering(cmd, {&color, 1}, depth, extent, area_rect);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS,
                    over_background ? over_background_pipeline_.get() : scene_pipeline_.get());
  vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, scene_pipeline_layout_.get(), 0, 1, &slot.frame_set, 0,
                          nullptr);
  shadow_passes_ = 0;
  if (over_background) {
    // The instruments change only where the sphere's shadow can fall and on the lit bars.
    const PixelRect shadow = shadow_rect(state);
    // Inside the frame's area only: false, and the scissor left as it was, when a rectangle
    // lies outside it (a pass there would draw nothing).
    auto scissor = [&](const PixelRect& p) {
      const PixelRect c = intersection(p, area);
      if (c.empty()) return false;
      const VkRect2D r{{c.x0, c.y0}, {static_cast<std::uint32_t>(c.x1 - c.x0), static_cast<std::uint32_t>(c.y1 - c.y0)}};
      vkCmdSetScissor(cmd, 0, 1, &r);
      return true;
    };
    std::vector<const Instance*> redrawn_lit;  // lit bars drawn again whole, with their light
    if (screen_space_shadow()) {
      // One triangle over each rectangle that changes (the shadow's, each lit detailed
      // bar's), whatever the models' triangles: each pixel's point, light, bar and shadow
      // come from the cache (shadow.frag).
      std::vector<PixelRect> changed;
      if (!shadow.empty()) changed.push_back(shadow);
      ShadowConstants sc{glm::inverse(view_proj_),
                         {1.0f / static_cast<float>(extent.width), 1.0f / static_cast<float>(extent.height), 0.0f,
                          0.0f},
                         glm::vec4(0.0f),
                         glm::vec4(0.0f),
                         glm::vec4(static_cast<float>(shadow.x0), static_cast<float>(shadow.y0),
                                   static_cast<float>(shadow.x1), static_cast<float>(shadow.y1))};
      int shaded_lights = 0;
      for (std::size_t k = 0; k < instruments_.size(); ++k) {
        const Instance& i = instruments_[k];
        if (glow_of(state, i.target) <= 0) continue;
        if (triangles_of(i) <= kRedrawLitBarTriangles || shaded_lights == 2) {
          redrawn_lit.push_back(&i);
          continue;
        }
        (shaded_lights == 0 ? sc.lit_a : sc.lit_b) = glm::vec4(static_cast<float>(i.target + 1), glow_light(state, i));
        ++shaded_lights;
        if (!instrument_rects_[k].empty()) changed.push_back(instrument_rects_[k]);
      }
      if (!changed.empty()) {
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shadow_pipeline_.get());
        const std::array<VkDescriptorSet, 2> sets{slot.frame_set, shadow_set_};
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, shadow_pipeline_layout_.get(), 0, 2,
                                sets.data(), 0, nullptr);
        vkCmdPushConstants(cmd, shadow_pipeline_layout_.get(), VK_SHADER_STAGE_FRAGMENT_BIT, 0, sizeof(sc), &sc);
        for (const PixelRect& p : changed) {  // where two overlap, both write the same value
          if (!scissor(p)) continue;
          vkCmdDraw(cmd, 3, 1, 0, 0);
          ++shadow_passes_;
        }
        vkCmdSetScissor(cmd, 0, 1, &area_rect);
        // Back to the scene's pipeline (and its layout's frame set) for the bars and the mallet.
        vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, over_background_pipeline_.get());
        vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, scene_pipeline_layout_.get(), 0, 1,
                                &slot.frame_set, 0, nullptr);
      }
    } else {
      // Multisampled frames, which need each sample's coverage at the bars' edges: the
      // instruments whose screen box meets the shadow's, redrawn where it darkens them (each
      // instance's box is projected once per image size).
      if (scissor(shadow)) {
        for (std::size_t k = 0; k < instruments_.size(); ++k)
          if (overlap(instrument_rects_[k], shadow)) {
            draw_instance(cmd, instruments_[k], Shadow::only_shadowed_pixels);
            ++shadow_passes_;
          }
        vkCmdSetScissor(cmd, 0, 1, &area_rect);
      }
      for (const Instance& i : instruments_)
        if (glow_of(state, i.target) > 0) redrawn_lit.push_back(&i);
    }
    // The other lit bars: single-sampled, their glow added over their own triangles to what
    // the cache and the shadow's pass left (glow.frag: scene.frag's emissive term, at a
    // constant's cost); multisampled, redrawn whole with their light and the shadow on them.
    const bool add_glow = screen_space_shadow() && !redrawn_lit.empty();
    if (add_glow) vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, glow_pipeline_.get());
    for (const Instance* i : redrawn_lit) draw_instance(cmd, *i, Shadow::receives, glow_light(state, *i));
    if (add_glow) vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, over_background_pipeline_.get());
  } else if (state.draw_instruments) {
    for (const Instance& i : instruments_) draw_instance(cmd, i, Shadow::receives, glow_light(state, i));
  }
  if (state.draw_mallet) {
    // Its hull, each pixel shaded as the exact sphere and blended over by its coverage.
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, sphere_pipeline_.get());
    draw_instance(cmd, mallet_hull(scene_, state.mallet_centre), Shadow::the_sphere);
  }
  if (state.overlay) draw_overlay(cmd, *state.overlay, slot, extent);
  vkCmdEndRendering(cmd);

  transition(cmd, target.image, VK_IMAGE_ASPECT_COLOR_BIT, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL,
             target.final_layout, color_stage, color_write, target.final_stage, target.final_access);
}

}  // namespace mallet::render
