#include "render/x11_image_put.hpp"

#include <utility>

#include <X11/Xlib.h>
#include <X11/Xutil.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#define GLFW_EXPOSE_NATIVE_X11
#include <GLFW/glfw3native.h>

namespace mallet::render {

struct X11ImagePut::Native {
  Display* display = nullptr;  // GLFW's connection: used on the thread that polls its events
  Window window = 0;
  Visual* visual = nullptr;
  int depth = 0;
  GC gc = nullptr;
};

X11ImagePut::X11ImagePut(std::unique_ptr<Native> native) : native_(std::move(native)) {}

X11ImagePut::~X11ImagePut() {
  if (native_ && native_->gc) XFreeGC(native_->display, native_->gc);
}

Result<std::unique_ptr<X11ImagePut>, std::string> X11ImagePut::open(GLFWwindow* window) {
  auto n = std::make_unique<Native>();
  n->display = glfwGetX11Display();
  n->window = n->display ? glfwGetX11Window(window) : 0;
  if (!n->display || !n->window) return refused("not an X11 window");
  XWindowAttributes a{};
  if (!XGetWindowAttributes(n->display, n->window, &a) || !a.visual) return refused("its attributes cannot be read");
  // A 32-bit pixel 0xAARRGGBB in the client's byte order (XInitImage below says which) is
  // the bytes B, G, R, A of VK_FORMAT_B8G8R8A8.
  const Visual& v = *a.visual;
  if (v.c_class != TrueColor || (a.depth != 24 && a.depth != 32) || v.red_mask != 0xff0000 ||
      v.green_mask != 0xff00 || v.blue_mask != 0xff)
    return refused("its visual is not 24-bit RGB TrueColor");
  int count = 0;
  bool bits32 = false;
  if (XPixmapFormatValues* formats = XListPixmapFormats(n->display, &count)) {
    for (int i = 0; i < count; ++i)
      if (formats[i].depth == a.depth) bits32 = formats[i].bits_per_pixel == 32;
    XFree(formats);
  }
  if (!bits32) return refused("its pixels are not 32 bits wide");
  n->visual = a.visual;
  n->depth = a.depth;
  n->gc = XCreateGC(n->display, n->window, 0, nullptr);
  if (!n->gc) return refused("no graphics context");
  return std::unique_ptr<X11ImagePut>(new X11ImagePut(std::move(n)));
}

void X11ImagePut::put(const std::uint8_t* pixels, int width, int height, std::size_t row_bytes, PixelRect area) {
  area = intersection(area, {0, 0, width, height});
  if (area.empty()) return;
  // An XImage over the caller's pixels (never freed through Xlib: XDestroyImage is not called).
  XImage image{};
  image.width = width;
  image.height = height;
  image.format = ZPixmap;
  image.data = const_cast<char*>(reinterpret_cast<const char*>(pixels));
  image.byte_order = LSBFirst;  // B, G, R, A in memory; Xlib swaps for a big-endian server
  image.bitmap_unit = 32;
  image.bitmap_bit_order = LSBFirst;
  image.bitmap_pad = 32;
  image.depth = native_->depth;
  image.bytes_per_line = static_cast<int>(row_bytes);
  image.bits_per_pixel = 32;
  image.red_mask = native_->visual->red_mask;
  image.green_mask = native_->visual->green_mask;
  image.blue_mask = native_->visual->blue_mask;
  if (!XInitImage(&image)) return;
  const auto w = static_cast<unsigned>(area.x1 - area.x0), h = static_cast<unsigned>(area.y1 - area.y0);
  XPutImage(native_->display, native_->window, native_->gc, &image, area.x0, area.y0, area.x0, area.y0, w, h);
  XFlush(native_->display);
  pixels_put_ += std::uint64_t{w} * h;
}

}  // namespace mallet::render
