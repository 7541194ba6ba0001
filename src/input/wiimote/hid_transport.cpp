#include "input/wiimote/hid_transport.hpp"

#include <cerrno>
#include <cstring>
#include <mutex>

#include <hidapi/hidapi.h>

namespace mallet::input::wiimote {

namespace {

//! hidapi's wide strings (serial, product, errors) as UTF-8.
std::string narrow(const wchar_t* text) {
  std::string out;
  if (!text) return out;
  for (; *text; ++text) {
    const auto c = static_cast<std::uint32_t>(*text);
    if (c < 0x80) {
      out += static_cast<char>(c);
    } else if (c < 0x800) {
      out += static_cast<char>(0xc0 | (c >> 6));
      out += static_cast<char>(0x80 | (c & 0x3f));
    } else if (c < 0x10000) {
      out += static_cast<char>(0xe0 | (c >> 12));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (c & 0x3f));
    } else if (c < 0x110000) {
      out += static_cast<char>(0xf0 | (c >> 18));
      out += static_cast<char>(0x80 | ((c >> 12) & 0x3f));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3f));
      out += static_cast<char>(0x80 | (c & 0x3f));
    } else {
      out += '?';
    }
  }
  return out;
}

//! hid_init is not thread-safe and is otherwise run implicitly by the first enumerate or
//! open, possibly on two threads at once (`wiimote list` beside a running device): run it
//! once, here. hid_exit is left to process exit (it only frees hidapi's statics).
bool init_hidapi() {
  static std::once_flag once;
  static int status = -1;
  std::call_once(once, [] { status = hid_init(); });
  return status == 0;
}

}  // namespace

std::vector<HidDeviceInfo> HidTransport::enumerate() {
  std::vector<HidDeviceInfo> out;
  if (!init_hidapi()) return out;
  // Ask for every Nintendo product and filter here: the list of products we drive is
  // ours (is_wii_remote), not hidapi's.
  hid_device_info* list = hid_enumerate(kNintendoVendorId, 0);
  for (const hid_device_info* d = list; d; d = d->next) {
    if (!is_wii_remote(d->vendor_id, d->product_id) || !d->path) continue;
    out.push_back({d->path, d->vendor_id, d->product_id, narrow(d->serial_number), narrow(d->product_string)});
  }
  hid_free_enumeration(list);
  return out;
}

OpenResult HidTransport::open(const std::string& path) {
  OpenResult result;
  if (!init_hidapi()) {
    result.error = "cannot start hidapi (hid_init failed): " + narrow(hid_error(nullptr));
    return result;
  }
  errno = 0;
  hid_device* device = hid_open_path(path.c_str());
  if (!device) {
    const int err = errno;
    std::string why = narrow(hid_error(nullptr));
    if (why.empty() && err != 0) why = std::strerror(err);
    if (why.empty()) why = "hid_open_path failed";
    result.error = "cannot open the Wii Remote at " + path + " (" + why + "); " + udev_hint();
    return result;
  }
  result.transport.reset(new HidTransport(device));
  return result;
}

HidTransport::~HidTransport() { hid_close(device_); }

bool HidTransport::write(std::span<const std::uint8_t> report) {
  if (report.empty()) return true;
  const int n = hid_write(device_, report.data(), report.size());
  return n >= 0;
}

int HidTransport::read(std::span<std::uint8_t> buffer, int timeout_ms) {
  const int n = hid_read_timeout(device_, buffer.data(), buffer.size(), timeout_ms);
  return n < 0 ? -1 : n;
}

}  // namespace mallet::input::wiimote
