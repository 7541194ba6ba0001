#pragma once
// A scene laid out for the screen's shape. A scene file describes a landscape scene: the
// instruments side by side in a rectangle of about 16:9. Framed on a portrait screen
// (1080 × 1920) that rectangle is a band of an eighth of the height. The portrait layout
// stacks the instruments instead, the first on top, each centred, each keeping the space
// above it to swing and below it for its near ends that it had; the wall and the texture
// disc keep their place and the content narrows to them. The kiosk, `mallet render` and
// `mallet simulate` choose it the same way (layout_for).
#include "core/scene.hpp"

namespace mallet {

//! `scene` (a landscape scene, as loaded) laid out for a portrait screen:
//!  - percussion: instrument k (in the file's order) moved down by k content heights and
//!    centred on the content's centre; the content is as wide as the widest instrument plus
//!    an eighth of its height on each side, and as tall as the rows; the eye is moved to
//!    their middle, as high above it as it was above the rows;
//!  - wall and texture: the content narrowed to the wall (or the disc) plus that margin.
//! The content never grows wider than it was. Targets keep their ids, notes and materials.
Scene portrait_layout(const Scene& scene);

//! The layout for a screen of `aspect` (width over height): portrait when the screen is
//! taller than wide and the portrait layout shows the scene's content larger there;
//! landscape otherwise (and when the aspect is not known: 0 or not finite).
SceneLayout layout_for(const Scene& scene, double aspect);

//! `scene` in `layout`: as it is for landscape, portrait_layout() for portrait.
Scene laid_out(const Scene& scene, SceneLayout layout);

//! A point of `file_scene`'s world (a hand over the scene as its file lays it out: a
//! trajectory, a recording) where it is over `laid` (laid_out(file_scene, ...)): moved as the
//! instrument it is over moved (the nearest one along x where it is between two), so that a
//! stroke onto a bar lands on that bar in either layout. Unmoved where nothing moved (a
//! landscape layout, the wall, the texture disc).
Vec2 to_layout(const Scene& file_scene, const Scene& laid, Vec2 world);

}  // namespace mallet
