#pragma once
// What a frame changes on the screen, so that only that is drawn. Over the cached
// instruments a frame shows the mallet head and its shadow, the lit bars and the overlay's
// text; when none of them changes, the picture on the screen is already right and the
// frame is not drawn at all (a still scene costs the loop's wake-ups, no drawing). When one
// does, a window's swapchain image still holds the frame it last showed, two to four frames
// ago: it is brought up to date by drawing again only the pixels that changed since, the
// union of each later frame's change (the head where it was and where it is, each bar whose
// light changed, the overlay's text where it changed). Pure bookkeeping, no GPU: the
// renderer describes each frame (FrameLook) and draws what commit() returns.
#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "core/bar_lights.hpp"
#include "render/overlay.hpp"
#include "render/scene_view.hpp"

namespace mallet::render {

//! A head that moved less than this on the screen since it was last drawn stays drawn where
//! it was: a 256th of a pixel, the rasteriser's own precision (lavapipe snaps vertices to
//! 1/256 px). Its slow drift adds up against the position drawn, so it is never left
//! further behind than that.
inline constexpr double kStillMalletPx = 1.0 / 256;
//! A lit bar whose glow changed less than this since it was drawn stays drawn as it was (a
//! fading bar's tail). The glow adds at most 0.8 of full light (a component of the
//! material's glow colour at 1, times the renderer's kGlowStrength), so this moves a lit
//! bar's pixels by at most one 8-bit level where they are brighter than 5 % of full light,
//! and by a few on its darkest faces. Its appearing
//! and its going out (below 1/255, core/bar_lights.hpp) are always drawn.
inline constexpr float kStillGlow = 1.0f / 512;

//! What one frame shows over the cached instruments, as far as it decides pixels.
struct FrameLook {
  int width = 0, height = 0;
  bool instruments = true;  //!< over the cached instruments (else a clear alone)
  bool mallet = false;
  Vec2 mallet_centre;         //!< the head's centre, world metres (as FrameState has it)
  glm::dvec2 mallet_px{0.0};  //!< the head's centre on the image, pixels
  PixelRect mallet_rect;      //!< the head and the shadow it casts
  BarLights lights{};
  std::array<PixelRect, kBarLights> light_rects{};  //!< each lit bar's on the image
  std::vector<OverlayVertex> overlay_vertices;
  std::vector<std::uint32_t> overlay_indices;
  const FontAtlas* overlay_atlas = nullptr;
  std::uint64_t overlay_atlas_generation = 0;  //!< the atlas's glyphs change as text is first shown
};

//! The pixels an overlay's shapes cover: their vertices' box, a pixel of margin, clamped.
PixelRect overlay_rect(const std::vector<OverlayVertex>& vertices, int width, int height);

//! The pixels that differ between the frame `before` and the frame `after` (one rectangle
//! holding every change; empty: the two are the same picture). The whole image when its
//! size or what it is drawn over changed.
PixelRect changed_between(const FrameLook& before, const FrameLook& after);

//! `next` with what moved less than a step since `drawn` (kStillMalletPx, kStillGlow) put
//! back as it was drawn: what a kept image goes on showing.
FrameLook settled(const FrameLook& drawn, FrameLook next);

class FrameDamage {
 public:
  //! How many frames back an image's content can be brought up to date from; an image
  //! older than that (or of unknown content) is drawn whole. Swapchains hold 2 to 4.
  static constexpr int kHistory = 8;

  //! Whether the frame `next` would differ from the last one committed, once settled (true
  //! before the first, and after forget()).
  bool changes(const FrameLook& next) const;
  //! `next` is about to be drawn into an image that holds the frame committed `age` frames
  //! before it (1: the last one; 0: unknown content). Returns the pixels to draw: every
  //! change since that frame, or the whole image. A kept image (age > 0) is drawn with
  //! `next` settled against the last frame (drawn()); a whole one exactly as `next`.
  PixelRect commit(FrameLook next, int age);
  //! The frame last committed, as it is drawn.
  const FrameLook& drawn() const { return *last_; }
  //! Nothing known of the images any more (new attachments, a new background): the next
  //! frame changes everything.
  void forget();

 private:
  std::optional<FrameLook> last_;
  std::array<PixelRect, kHistory> changed_{};  //!< changed_[n % kHistory]: frame n's change
  std::uint64_t frames_ = 0;                   //!< frames committed
};

}  // namespace mallet::render
