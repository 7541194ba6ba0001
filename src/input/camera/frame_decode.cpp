#include "input/camera/frame_decode.hpp"

#include <fmt/format.h>

#include "input/camera/jpeg_error.hpp"

namespace mallet::input::camera {

namespace {

// Frames larger than this are a driver's or a file's nonsense, not a camera's: refusing them
// keeps width × height × 2 far from overflowing and a scratch from growing without bound.
constexpr int kMaxSide = 16384;

const char* name_of(PixelFormat f) { return name_in(kPixelFormatNames, f); }

// Decodes `data` to grayscale rows in `scratch`. No C++ object with a destructor lives
// between setjmp and a longjmp here (the jump would skip it); scratch is resized before
// any libjpeg call can jump, and only read by the caller after a normal return.
// Returns 0, or 1 with err.message set, or 2 when the JPEG's size is not width × height
// (then *got_w, *got_h say what it is).
int decode_gray(const std::uint8_t* data, std::size_t size, int width, int height, std::uint8_t* out,
                JpegError& err, int* got_w, int* got_h) {
  jpeg_decompress_struct cinfo;
  cinfo.err = jpeg_error_init(err);
  if (setjmp(err.jump)) {
    jpeg_destroy_decompress(&cinfo);
    return 1;
  }
  jpeg_create_decompress(&cinfo);
  jpeg_mem_src(&cinfo, data, static_cast<unsigned long>(size));
  jpeg_read_header(&cinfo, TRUE);
  // UVC cameras leave out the Huffman tables (Motion-JPEG's convention); libjpeg-turbo
  // supplies the standard ones, so no DHT needs splicing in here.
  cinfo.out_color_space = JCS_GRAYSCALE;
  if (static_cast<int>(cinfo.image_width) != width || static_cast<int>(cinfo.image_height) != height) {
    *got_w = static_cast<int>(cinfo.image_width);
    *got_h = static_cast<int>(cinfo.image_height);
    jpeg_destroy_decompress(&cinfo);
    return 2;
  }
  jpeg_start_decompress(&cinfo);
  while (cinfo.output_scanline < cinfo.output_height) {
    JSAMPROW row = out + static_cast<std::size_t>(cinfo.output_scanline) * static_cast<std::size_t>(width);
    jpeg_read_scanlines(&cinfo, &row, 1);
  }
  jpeg_finish_decompress(&cinfo);
  jpeg_destroy_decompress(&cinfo);
  return 0;
}

}  // namespace

Result<LumaView, std::string> luma_view(const CameraFrame& frame, std::vector<std::uint8_t>& scratch) {
  const int w = frame.width, h = frame.height;
  if (w < 1 || h < 1 || w > kMaxSide || h > kMaxSide)
    return refused(fmt::format("a {}x{} {} frame: width and height must be 1..{}", w, h, name_of(frame.format), kMaxSide));

  if (frame.format == PixelFormat::mjpeg) {
    if (frame.bytes.empty()) return refused(fmt::format("mjpeg frame: empty ({}x{} expected)", w, h));
    scratch.resize(static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
    JpegError err;
    int got_w = 0, got_h = 0;
    const int rc = decode_gray(frame.bytes.data(), frame.bytes.size(), w, h, scratch.data(), err, &got_w, &got_h);
    if (rc == 1) return refused(fmt::format("mjpeg frame: {}", err.message));
    if (rc == 2) return refused(fmt::format("mjpeg frame is {}x{}, the camera said {}x{}", got_w, got_h, w, h));
    return LumaView{w, h, scratch.data(), w, 1};
  }

  const int step = frame.format == PixelFormat::yuyv ? 2 : 1;
  const std::size_t row_bytes = static_cast<std::size_t>(w) * static_cast<std::size_t>(step);
  const std::size_t stride = frame.bytes_per_line ? frame.bytes_per_line : row_bytes;
  if (stride < row_bytes)
    return refused(fmt::format("a {}x{} {} frame: bytes_per_line {} is less than a row's {} bytes", w, h,
                               name_of(frame.format), stride, row_bytes));
  // The last row need not carry its padding (some drivers' sizeimage stops at the pixels).
  const std::size_t needed = stride * static_cast<std::size_t>(h - 1) + row_bytes;
  if (frame.bytes.size() < needed)
    return refused(fmt::format("a {}x{} {} frame needs {} bytes, this one has {}", w, h, name_of(frame.format), needed,
                               frame.bytes.size()));
  return LumaView{w, h, frame.bytes.data(), static_cast<std::ptrdiff_t>(stride), step};
}

}  // namespace mallet::input::camera
