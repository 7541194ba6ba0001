#pragma once
// Camera → screen calibration: the plane-to-plane projective map (homography) from the
// Wii Remote's raw IR camera pixels (x 0..1023, y 0..767, not mirrored) to normalised
// screen coordinates (0..1, origin top-left). Mirroring and rotation of the camera are
// just part of the matrix.
//
// Fitting is the normalised Direct Linear Transform (Hartley & Zisserman, "Multiple View
// Geometry", 2nd ed., Alg. 4.2): both point sets are moved to their centroid and scaled to a
// mean distance of √2, the 2n×9 system A·h = 0 is solved by SVD (h = the right singular
// vector of the smallest singular value), and the result is de-normalised. With exactly 4
// points the fit is exact; with more it minimises the algebraic error in least squares.
//
// Points come from a visitor's calibration session, so bad data is never asserted on and
// never thrown: fit_homography returns the reason as one sentence instead.
#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "core/geometry.hpp"
#include "core/result.hpp"

namespace mallet {

//! The screen the normalised coordinates stand for; reprojection errors are in its pixels.
struct ScreenSize {
  double width_px = 1920.0;
  double height_px = 1080.0;
  friend bool operator==(const ScreenSize&, const ScreenSize&) = default;
};

//! A 3×3 projective map, row-major: [x'w, y'w, w] = H · [x, y, 1].
struct Homography {
  std::array<double, 9> h{1, 0, 0, 0, 1, 0, 0, 0, 1};

  //! The image of p; {NaN, NaN} where p lies on the line the map sends to infinity.
  Vec2 map(Vec2 p) const;
  //! The image of p, or nothing where it is not finite (w ≈ 0, or non-finite input).
  std::optional<Vec2> try_map(Vec2 p) const;
  //! The inverse map (scaled so h33 = 1 where possible), or nothing if H is singular.
  std::optional<Homography> inverse() const;
  double determinant() const;
};

struct HomographyFit {
  Homography h;                             //!< from → to (to = normalised screen)
  ScreenSize screen;                        //!< what the pixel errors below are measured in
  //! Per point |H(from_i) − to_i|, in screen pixels (to scaled by the screen size).
  std::vector<double> reprojection_error_px;
  double rms_px = 0.0;
  double max_px = 0.0;
  //! Per point |H⁻¹(to_i) − from_i|, in the units of `from` (camera pixels).
  std::vector<double> camera_error_px;
  double camera_rms_px = 0.0;
  double camera_max_px = 0.0;
};

//! Smallest "flatness" (distance of a point from the line through two others, divided by
//! the longest side of their triangle) that still counts as not collinear: 1 %.
inline constexpr double kCollinearTolerance = 1e-2;

//! Fits H with H(from_i) ≈ to_i. `to` is in normalised screen units; the fit is done in
//! `screen` pixels so that the isotropic normalisation matches how errors are measured.
//! Refused (with the reason) when: the spans differ in length, fewer than 4 points, a
//! coordinate is NaN or infinite, two points repeat, no 4 points are in general position
//! (with 4 points: any 3 collinear within kCollinearTolerance, on either side), the
//! linear system is rank deficient, the fit is singular, or the points straddle the line
//! the fit sends to infinity (a "folded" fit, usually points given in the wrong order).
Result<HomographyFit, std::string> fit_homography(std::span<const Vec2> from, std::span<const Vec2> to,
                                                  ScreenSize screen = {});

}  // namespace mallet
