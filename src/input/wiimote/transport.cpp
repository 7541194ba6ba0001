#include "input/wiimote/transport.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>

#include <fmt/format.h>

namespace mallet::input::wiimote {

std::string udev_hint() {
  return "the remote's /dev/hidraw* node must be readable and writable by this user (permission denied?): "
         "the mallet package installs the udev rule " +
         std::string(kUdevRulePath) + "; without the package, create " + std::string(kLocalUdevRulePath) +
         " containing\n    " + std::string(kUdevRule) +
         "\nthen run `sudo udevadm control --reload && sudo udevadm trigger` and reconnect the remote";
}

std::string product_name(std::uint16_t product_id) {
  if (product_id == kWiiRemoteProductId) return "RVL-CNT-01";
  if (product_id == kWiiRemoteTrProductId) return "RVL-CNT-01-TR";
  return fmt::format("0x{:04x}", static_cast<unsigned>(product_id));
}

bool matches_device(const HidDeviceInfo& device, std::string_view filter) {
  if (filter.empty()) return true;
  auto contains = [filter](const std::string& text) {
    const auto it = std::search(text.begin(), text.end(), filter.begin(), filter.end(), [](char a, char b) {
      return std::tolower(static_cast<unsigned char>(a)) == std::tolower(static_cast<unsigned char>(b));
    });
    return it != text.end();
  };
  return contains(device.path) || contains(device.serial);
}

std::optional<HidDeviceInfo> first_matching(const std::vector<HidDeviceInfo>& devices, std::string_view filter) {
  const auto it = std::find_if(devices.begin(), devices.end(),
                               [filter](const HidDeviceInfo& d) { return matches_device(d, filter); });
  if (it == devices.end()) return std::nullopt;
  return *it;
}

std::string remote_identity(const HidDeviceInfo& device) {
  return device.serial.empty() ? device.path : device.serial;
}

}  // namespace mallet::input::wiimote
