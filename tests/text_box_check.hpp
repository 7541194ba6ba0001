#pragma once
// The overlap contract's check (issue 48, item 4), for the tests that draw a screen's words:
// no text drawn over another, none leaving the screen, as the overlay recorded every text's
// ink (render::Overlay::text_boxes). And the four screen shapes the walkthroughs use.
#include <string>
#include <utility>
#include <vector>

#include "render/overlay.hpp"

namespace mallet::test {

//! 16:9, 5:4, 9:16 and 21:9, in pixels.
inline constexpr std::pair<float, float> kWalkShapes[] = {{1920.0f, 1080.0f}, {1280.0f, 1024.0f},
                                                           {1080.0f, 1920.0f}, {2560.0f, 1080.0f}};

//! One line for every pair of texts drawn over each other ("\"A\" over \"B\"") and every text
//! reaching off a width×height screen ("\"A\" leaves the screen"), in the order drawn.
inline std::vector<std::string> text_box_problems(const render::Overlay& overlay, float width, float height) {
  std::vector<std::string> problems;
  const std::vector<render::TextBox>& boxes = overlay.text_boxes();
  for (std::size_t i = 0; i < boxes.size(); ++i) {
    const render::TextBox& a = boxes[i];
    if (a.x0 < 0 || a.y0 < 0 || a.x1 > width || a.y1 > height)
      problems.push_back("\"" + a.text + "\" leaves the screen");
    for (std::size_t j = i + 1; j < boxes.size(); ++j)
      if (render::overlap(a, boxes[j])) problems.push_back("\"" + a.text + "\" over \"" + boxes[j].text + "\"");
  }
  return problems;
}

}  // namespace mallet::test
