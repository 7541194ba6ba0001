#pragma once
// The stick's IR LED in a camera frame: a threshold adapted to the frame, 8-connected
// components, an intensity-weighted subpixel centroid, and rejection of what is not the
// LED (a reflection, a second light, a lamp or a sunlit wall) by size and shape.
//
// Per call: the region is a square of roi_radius_px around where the LED should be now
// (its last position plus its last step) while tracking, else the whole frame; when the
// square holds no acceptable blob, the whole frame is searched in the same call. Within a
// region: the background is the median of a subsample, the threshold the larger of
// background + min_contrast and background + threshold_fraction × (peak − background);
// pixels at or above it form runs, runs form components (union–find, no recursion), and
// each component's moments give its area, integrated intensity and elongation. The LED is,
// among the acceptable components, the nearest to the prediction while tracking, and the
// one with the largest integrated intensity when acquiring (the LED is the strongest source
// in an 850 nm-filtered view; its reflections are dimmer). While tracking, in the square
// and in the full search after it, a blob below track_min_sum_ratio of the LED's last
// integrated intensity is not taken; once the LED is lost, the next frame takes the
// strongest blob whatever it is (a jump the IR tracker downstream judges). The chosen
// blob's centroid is then refined over its bounding box grown by half its size and
// centroid_margin_px (but less than halfway to another blob), background subtracted, so
// that the Gaussian's shoulders below the threshold count too (less bias toward pixel
// centres).
//
// Buffers grow to the largest frame's needs and are reused: no allocation per frame in
// steady state. Device-free; one finder per camera, one thread.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "core/result.hpp"
#include "input/camera/camera_frame.hpp"

namespace mallet::input::camera {

//! Defaults for an 850 nm-filtered camera at 640×480 with a short exposure (≤ 1 ms), where
//! the LED is a 3–15 px blob well above a dark background.
struct LedFinderConfig {
  int min_contrast = 40;            //!< grey levels above the background a pixel needs to count (noise is ≈ 2)
  double threshold_fraction = 0.4;  //!< of (peak − background): the threshold follows a brighter or dimmer LED
  int min_area_px = 3;              //!< smaller: a hot pixel or a glint
  int max_area_px = 400;            //!< larger: a lamp, a window, a sunlit surface (a 15 px LED blurred is ≈ 250)
  double max_elongation = 3.0;      //!< ratio of the 2nd-moment axes; a blurred LED at 4 m/s is < 1.6
  int roi_radius_px = 48;           //!< half the tracking square: 4 m/s at 240 Hz is ≈ 13 px a frame
  int centroid_margin_px = 2;       //!< the centroid's window: the bounding box grown by half its size and this
  double track_min_sum_ratio = 0.35;  //!< while tracking, a blob dimmer than this × the LED's last is not it
  int max_runs = 20000;             //!< more runs above threshold in one region: a cluttered frame, refused
};

//! Whether `config` can be used: passed, or one line naming the bad key.
Check validate(const LedFinderConfig& config);

//! A component, measured. Pixel centres are at integer coordinates.
struct LedBlob {
  double x = 0, y = 0;     //!< intensity-weighted centroid, background subtracted, px
  int area_px = 0;         //!< pixels at or above the threshold
  double sum = 0;          //!< Σ (luma − background) over those pixels
  int peak = 0;            //!< brightest luma
  double elongation = 1;   //!< √(λ₁/λ₂) of the intensity-weighted 2nd moments (1 = round)
};

//! Why candidates were not the LED.
struct LedRejections {
  int too_small = 0;
  int too_large = 0;
  int elongated = 0;
  int too_dim = 0;     //!< while tracking, below track_min_sum_ratio of the LED's last sum
  int cluttered = 0;   //!< regions given up: more than max_runs runs above the threshold
  int total() const { return too_small + too_large + elongated + too_dim; }
};

//! What one call found. Counts are those of the last region searched (the whole frame
//! after an empty tracking square, since it holds the square).
struct LedFind {
  std::optional<LedBlob> led;  //!< none: no acceptable blob anywhere (the LED is lost)
  bool full_search = false;    //!< the whole frame was searched (acquiring, or the square was empty)
  int candidates = 0;          //!< components found
  LedRejections rejected;
  int background = 0;          //!< grey level the threshold was set from
  int threshold = 0;           //!< 0: the region had no pixel min_contrast above its background
};

//! Totals since construction.
struct LedFinderCounters {
  std::uint64_t frames = 0;
  std::uint64_t found = 0;
  std::uint64_t full_searches = 0;
  std::uint64_t roi_misses = 0;  //!< tracking squares without the LED (then a full search)
  std::uint64_t lost = 0;        //!< frames where the LED was found nowhere
  LedRejections rejected;        //!< summed over all calls
};

class LedFinder {
 public:
  //! Throws std::invalid_argument (validate's line) for a bad config.
  explicit LedFinder(LedFinderConfig config = {});

  //! The LED in `luma` (any size, 1×1 included; an empty view finds nothing).
  LedFind find(const LumaView& luma);
  //! Forget the track: the next find searches the whole frame.
  void reset();
  //! Totals since construction.
  const LedFinderCounters& counters() const { return counters_; }
  const LedFinderConfig& config() const { return config_; }

 private:
  struct Region {
    int x0, y0, x1, y1;  // inclusive
  };
  struct Run {
    int y, x0, x1;  // inclusive
    int parent;
  };
  struct Moments {
    double s = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    int area = 0, peak = 0;
    double elongation = 1;
  };

  bool search(const LumaView& luma, const Region& r, bool nearest, LedFind& out);
  int find_root(int i);
  LedBlob refine(const LumaView& luma, const Moments& m, int background, const Region& box) const;

  LedFinderConfig config_;
  LedFinderCounters counters_;
  std::optional<LedBlob> last_;
  double step_x_ = 0, step_y_ = 0;  // the LED's last move, px per frame
  std::vector<Run> runs_;
  std::vector<Moments> comps_;
  std::vector<Region> boxes_;
  std::vector<int> comp_of_root_;
  std::vector<std::uint8_t> row_max_;
};

}  // namespace mallet::input::camera
