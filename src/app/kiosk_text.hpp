#pragma once
// What the kiosk writes and shows in words, shared by the window and the headless run: the
// log line of a strike and the one-line banner (the invitation, the hints).
#include <string>
#include <string_view>

#include "core/impact.hpp"
#include "core/scene.hpp"
#include "render/overlay.hpp"

namespace mallet::app {

//! "strike t=12.345678901 bar=3 xylophone note=77 speed=1.200 m/s"
std::string strike_line(const Scene& scene, const Impact& impact);

//! The text centred near the top of a width×height screen, on a translucent band.
void draw_banner(render::Overlay& overlay, std::string_view text, float width, float height);

}  // namespace mallet::app
