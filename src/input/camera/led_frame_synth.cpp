#include "input/camera/led_frame_synth.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>

#include <fmt/format.h>

#include "input/camera/jpeg_error.hpp"

namespace mallet::input::camera {

double spot_level(const SynthSpot& s, double exposure_s, double x, double y) {
  const double dx = x - s.x, dy = y - s.y;
  const double inv2s2 = 1.0 / (2.0 * s.sigma_px * s.sigma_px);
  const double speed = std::hypot(s.vx_px_per_s, s.vy_px_per_s);
  const double blur = speed * exposure_s;  // px travelled during the exposure
  if (blur < 1e-6) return s.peak * std::exp(-(dx * dx + dy * dy) * inv2s2);
  // Along the motion: the Gaussian averaged over the path [−blur/2, +blur/2] (erf);
  // across it: the Gaussian unchanged.
  const double ux = s.vx_px_per_s / speed, uy = s.vy_px_per_s / speed;
  const double along = dx * ux + dy * uy;
  const double across = -dx * uy + dy * ux;
  const double k = 1.0 / (s.sigma_px * std::numbers::sqrt2);
  const double mean_along = s.sigma_px * std::sqrt(std::numbers::pi / 2.0) / blur *
                            (std::erf((along + blur / 2) * k) - std::erf((along - blur / 2) * k));
  return s.peak * std::exp(-across * across * inv2s2) * mean_along;
}

double LedFrameSynth::normal() {
  if (spare_) {
    const double z = *spare_;
    spare_.reset();
    return z;
  }
  // u in (0, 1), never 0: log(u) stays finite.
  const double u1 = (static_cast<double>(rng_()) + 0.5) / 4294967296.0;
  const double u2 = (static_cast<double>(rng_()) + 0.5) / 4294967296.0;
  const double r = std::sqrt(-2.0 * std::log(u1));
  spare_ = r * std::sin(2.0 * std::numbers::pi * u2);
  return r * std::cos(2.0 * std::numbers::pi * u2);
}

void LedFrameSynth::render(const SynthScene& scene, std::vector<std::uint8_t>& luma) {
  const int w = std::max(scene.width, 0), h = std::max(scene.height, 0);
  const std::size_t n = static_cast<std::size_t>(w) * static_cast<std::size_t>(h);
  std::vector<float> signal(n, 0.0f);
  // Each spot only where it is above 1e-4 of its peak: 4.3 σ plus half its blur.
  for (const SynthSpot& s : scene.spots) {
    const double reach = 4.3 * s.sigma_px + 0.5 * std::hypot(s.vx_px_per_s, s.vy_px_per_s) * scene.exposure_s + 1;
    const int x0 = std::max(0, static_cast<int>(std::floor(s.x - reach)));
    const int x1 = std::min(w - 1, static_cast<int>(std::ceil(s.x + reach)));
    const int y0 = std::max(0, static_cast<int>(std::floor(s.y - reach)));
    const int y1 = std::min(h - 1, static_cast<int>(std::ceil(s.y + reach)));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x)
        signal[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)] +=
            static_cast<float>(spot_level(s, scene.exposure_s, x, y));
  }
  luma.resize(n);
  const double read_var = scene.read_noise * scene.read_noise;
  for (std::size_t i = 0; i < n; ++i) {
    const double sig = signal[i];
    const double sigma = std::sqrt(read_var + scene.shot_variance_per_level * std::max(sig, 0.0));
    const double v = std::round(scene.background + sig + sigma * normal());
    luma[i] = static_cast<std::uint8_t>(std::clamp(v, 0.0, 255.0));
  }
}

namespace {

// Encodes `rgb` (w × h × 3) into *out (malloc'd by libjpeg). 0, or 1 with err.message set.
// No C++ object with a destructor lives between setjmp and the libjpeg calls.
int encode_rgb(const std::uint8_t* rgb, int w, int h, int quality, JpegError& err, unsigned char** out,
               unsigned long* out_size) {
  jpeg_compress_struct cinfo;
  cinfo.err = jpeg_error_init(err);
  if (setjmp(err.jump)) {
    jpeg_destroy_compress(&cinfo);
    return 1;
  }
  jpeg_create_compress(&cinfo);
  jpeg_mem_dest(&cinfo, out, out_size);
  cinfo.image_width = static_cast<JDIMENSION>(w);
  cinfo.image_height = static_cast<JDIMENSION>(h);
  cinfo.input_components = 3;
  cinfo.in_color_space = JCS_RGB;
  jpeg_set_defaults(&cinfo);
  jpeg_set_quality(&cinfo, quality, TRUE);
  // 4:2:2, as UVC webcams send it (libjpeg's default is 4:2:0).
  cinfo.comp_info[0].h_samp_factor = 2;
  cinfo.comp_info[0].v_samp_factor = 1;
  jpeg_start_compress(&cinfo, TRUE);
  while (cinfo.next_scanline < cinfo.image_height) {
    auto row = const_cast<JSAMPROW>(rgb + static_cast<std::size_t>(cinfo.next_scanline) * static_cast<std::size_t>(w) * 3);
    jpeg_write_scanlines(&cinfo, &row, 1);
  }
  jpeg_finish_compress(&cinfo);
  jpeg_destroy_compress(&cinfo);
  return 0;
}

}  // namespace

Result<std::vector<std::uint8_t>, std::string> encode_frame(const std::vector<std::uint8_t>& luma, int width,
                                                            int height, PixelFormat format,
                                                            std::size_t bytes_per_line, int jpeg_quality) {
  const std::size_t w = static_cast<std::size_t>(std::max(width, 0)), h = static_cast<std::size_t>(std::max(height, 0));
  if (luma.size() != w * h) return refused(fmt::format("{} luma bytes for a {}x{} frame", luma.size(), width, height));
  switch (format) {
    case PixelFormat::grey: {
      const std::size_t stride = std::max(bytes_per_line, w);
      std::vector<std::uint8_t> out(stride * h, 0);
      for (std::size_t y = 0; y < h; ++y) std::copy_n(luma.begin() + static_cast<std::ptrdiff_t>(y * w), w, out.begin() + static_cast<std::ptrdiff_t>(y * stride));
      return out;
    }
    case PixelFormat::yuyv: {
      const std::size_t stride = std::max(bytes_per_line, 2 * w);
      std::vector<std::uint8_t> out(stride * h, 0);
      for (std::size_t y = 0; y < h; ++y)
        for (std::size_t x = 0; x < w; ++x) {
          out[y * stride + 2 * x] = luma[y * w + x];
          out[y * stride + 2 * x + 1] = 128;  // U or V: no colour under an 850 nm filter
        }
      return out;
    }
    case PixelFormat::mjpeg: {
      if (w == 0 || h == 0) return refused("an empty frame cannot be a JPEG");
      std::vector<std::uint8_t> rgb(w * h * 3);
      for (std::size_t i = 0; i < w * h; ++i) rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = luma[i];
      JpegError err;
      unsigned char* buf = nullptr;
      unsigned long size = 0;
      const int rc = encode_rgb(rgb.data(), width, height, std::clamp(jpeg_quality, 1, 100), err, &buf, &size);
      std::vector<std::uint8_t> out;
      if (rc == 0) out.assign(buf, buf + size);
      std::free(buf);  // jpeg_mem_dest's buffer is malloc'd, and ours to free
      if (rc != 0) return refused(fmt::format("mjpeg encode: {}", err.message));
      return out;
    }
  }
  return refused("unknown pixel format");
}

}  // namespace mallet::input::camera
