// The fake libhidapi-hidraw behind fake_hidapi.hpp. Only what HidTransport uses; every
// other hid_* function is left undefined so a new use fails to link instead of faking.
#include "fake_hidapi.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <cwchar>
#include <deque>
#include <map>
#include <mutex>

#include <hidapi/hidapi.h>

struct hid_device_ {
  std::string path;
};

namespace fake_hidapi {
namespace {

struct PathState {
  std::deque<Bytes> reports;  //!< scripted
  std::deque<Bytes> answers;  //!< the remote's answers to writes, delivered first
  std::vector<Bytes> written;
  int reads_left = -1;        //!< -1: never gone
  bool answers_on = false;
  int open_errno = 0;
  std::wstring open_message;
};

struct World {
  std::mutex mutex;
  std::vector<Device> devices;
  std::map<std::string, PathState> paths;
  std::vector<std::pair<unsigned short, unsigned short>> enumerations;
  int open = 0;
  int closed = 0;
  std::wstring last_error;
  std::function<void(int, int)> read_hook;
};

World& world() {
  static World w;
  return w;
}

bool gone(const PathState& s) { return s.reads_left == 0; }

}  // namespace

void reset() {
  World& w = world();
  std::lock_guard lock(w.mutex);
  w.devices.clear();
  w.paths.clear();
  w.enumerations.clear();
  w.open = 0;
  w.closed = 0;
  w.last_error.clear();
  w.read_hook = nullptr;
}

void add_device(const Device& device) {
  std::lock_guard lock(world().mutex);
  world().devices.push_back(device);
}

void fail_open(const std::string& path, int error_number, const std::wstring& message) {
  std::lock_guard lock(world().mutex);
  world().paths[path].open_errno = error_number;
  world().paths[path].open_message = message;
}

void push_report(const std::string& path, Bytes report) {
  std::lock_guard lock(world().mutex);
  world().paths[path].reports.push_back(std::move(report));
}

void gone_after_reads(const std::string& path, int reads) {
  std::lock_guard lock(world().mutex);
  world().paths[path].reads_left = reads;
}

void set_answers(const std::string& path, bool answers) {
  std::lock_guard lock(world().mutex);
  world().paths[path].answers_on = answers;
}

std::vector<Bytes> writes(const std::string& path) {
  std::lock_guard lock(world().mutex);
  return world().paths[path].written;
}

std::vector<std::pair<unsigned short, unsigned short>> enumerate_calls() {
  std::lock_guard lock(world().mutex);
  return world().enumerations;
}

int open_count() {
  std::lock_guard lock(world().mutex);
  return world().open;
}

int close_count() {
  std::lock_guard lock(world().mutex);
  return world().closed;
}

void set_read_hook(std::function<void(int, int)> hook) {
  std::lock_guard lock(world().mutex);
  world().read_hook = std::move(hook);
}

}  // namespace fake_hidapi

using fake_hidapi::world;

extern "C" {

int HID_API_EXPORT HID_API_CALL hid_init(void) { return 0; }
int HID_API_EXPORT HID_API_CALL hid_exit(void) { return 0; }

struct hid_device_info HID_API_EXPORT* HID_API_CALL hid_enumerate(unsigned short vendor_id, unsigned short product_id) {
  auto& w = world();
  std::lock_guard lock(w.mutex);
  w.enumerations.emplace_back(vendor_id, product_id);
  hid_device_info* head = nullptr;
  hid_device_info** tail = &head;
  for (const auto& d : w.devices) {
    if ((vendor_id && d.vendor_id != vendor_id) || (product_id && d.product_id != product_id)) continue;
    auto* info = static_cast<hid_device_info*>(std::calloc(1, sizeof(hid_device_info)));
    info->path = strdup(d.path.c_str());
    info->vendor_id = d.vendor_id;
    info->product_id = d.product_id;
    info->serial_number = wcsdup(d.serial.c_str());
    info->manufacturer_string = wcsdup(L"Nintendo");
    info->product_string = wcsdup(d.product.c_str());
    info->bus_type = HID_API_BUS_BLUETOOTH;
    *tail = info;
    tail = &info->next;
  }
  return head;
}

void HID_API_EXPORT HID_API_CALL hid_free_enumeration(struct hid_device_info* devs) {
  while (devs) {
    hid_device_info* next = devs->next;
    std::free(devs->path);
    std::free(devs->serial_number);
    std::free(devs->manufacturer_string);
    std::free(devs->product_string);
    std::free(devs);
    devs = next;
  }
}

HID_API_EXPORT hid_device* HID_API_CALL hid_open_path(const char* path) {
  auto& w = world();
  std::lock_guard lock(w.mutex);
  auto& s = w.paths[path];
  if (s.open_errno != 0) {
    errno = s.open_errno;
    w.last_error = s.open_message;
    return nullptr;
  }
  bool listed = false;
  for (const auto& d : w.devices) listed = listed || d.path == path;
  if (!listed) {
    errno = ENOENT;
    w.last_error = L"No such file or directory";
    return nullptr;
  }
  ++w.open;
  return new hid_device_{path};
}

void HID_API_EXPORT HID_API_CALL hid_close(hid_device* dev) {
  if (!dev) return;
  {
    auto& w = world();
    std::lock_guard lock(w.mutex);
    --w.open;
    ++w.closed;
  }
  delete dev;
}

int HID_API_EXPORT HID_API_CALL hid_write(hid_device* dev, const unsigned char* data, size_t length) {
  auto& w = world();
  std::lock_guard lock(w.mutex);
  auto& s = w.paths[dev->path];
  if (gone(s)) return -1;
  fake_hidapi::Bytes b(data, data + length);
  s.written.push_back(b);
  if (s.answers_on && length >= 2) {
    if (b[0] == 0x15) s.answers.push_back({0x20, 0x00, 0x00, 0x08, 0x00, 0x00, 0xc8});
    else if (b[0] == 0x16 || (b[1] & 0x02) != 0) s.answers.push_back({0x22, 0x00, 0x00, b[0], 0x00});
  }
  return static_cast<int>(length);
}

int HID_API_EXPORT HID_API_CALL hid_read_timeout(hid_device* dev, unsigned char* data, size_t length, int milliseconds) {
  auto& w = world();
  std::function<void(int, int)> hook;
  int result = 0;
  {
    std::lock_guard lock(w.mutex);
    hook = w.read_hook;
    auto& s = w.paths[dev->path];
    std::deque<fake_hidapi::Bytes>* from = !s.answers.empty() ? &s.answers : !s.reports.empty() ? &s.reports : nullptr;
    if (gone(s)) {
      result = -1;
    } else if (from) {
      const fake_hidapi::Bytes b = std::move(from->front());
      from->pop_front();
      const std::size_t n = std::min(b.size(), length);
      std::memcpy(data, b.data(), n);
      result = static_cast<int>(n);
      if (s.reads_left > 0) --s.reads_left;
    }
  }
  if (hook) hook(milliseconds, result);
  return result;
}

HID_API_EXPORT const wchar_t* HID_API_CALL hid_error(hid_device* dev) {
  (void)dev;
  return world().last_error.c_str();
}

}  // extern "C"
