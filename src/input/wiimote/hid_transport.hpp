#pragma once
// The real Wii Remote link: hidapi on Linux hidraw (Debian: libhidapi-dev, pkg-config
// hidapi-hidraw). A thin RAII owner of one hid_device; hid_transport.cpp is the only file
// of the program that includes hidapi, and it lives in its own library (mallet_hid) so a
// test can link it against a fake hidapi instead (hid_open_path on anything but a real
// hidraw node crashes libhidapi 0.13).
//
// On Linux, hidraw writes go out on the Bluetooth interrupt channel, which the -TR model
// (0x0330) requires; byte 0 of every buffer is the report id, both ways.
#include <string>
#include <vector>

#include "input/wiimote/transport.hpp"

struct hid_device_;  // hidapi's opaque device (hid_device)

namespace mallet::input::wiimote {

class HidTransport final : public Transport {
 public:
  //! Every Wii Remote present (vendor 0x057e, products 0x0306 and 0x0330; other Nintendo
  //! devices are left out), in hidapi's order. Empty when none (or hidapi cannot start).
  static std::vector<HidDeviceInfo> enumerate();
  //! Opens the hidraw node `path`; on failure the error names the path, hidapi's reason
  //! and the udev hint.
  static OpenResult open(const std::string& path);

  ~HidTransport() override;
  HidTransport(const HidTransport&) = delete;
  HidTransport& operator=(const HidTransport&) = delete;

  bool write(std::span<const std::uint8_t> report) override;
  int read(std::span<std::uint8_t> buffer, int timeout_ms) override;

 private:
  explicit HidTransport(hid_device_* device) : device_(device) {}
  hid_device_* device_;
};

//! The DeviceFinder of the running kiosk: HidTransport's enumerate() and open().
class HidDeviceFinder final : public DeviceFinder {
 public:
  std::vector<HidDeviceInfo> enumerate() override { return HidTransport::enumerate(); }
  OpenResult open(const std::string& path) override { return HidTransport::open(path); }
};

}  // namespace mallet::input::wiimote
