#pragma once
// The Wii Remote's link as two small interfaces, so the device logic (wiimote_device.hpp)
// runs the same against hidapi (hid_transport.hpp) and against an in-process fake in the
// tests. Byte 0 of every buffer is the report id, as hidraw takes and returns it.
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace mallet::input::wiimote {

inline constexpr std::uint16_t kNintendoVendorId = 0x057e;
inline constexpr std::uint16_t kWiiRemoteProductId = 0x0306;    //!< RVL-CNT-01
inline constexpr std::uint16_t kWiiRemoteTrProductId = 0x0330;  //!< RVL-CNT-01-TR (Motion Plus inside)

//! The two products this program drives (the Wii U Pro Controller, the Balance Board's
//! sibling ids etc. are not IR pointers).
constexpr bool is_wii_remote(std::uint16_t vendor_id, std::uint16_t product_id) {
  return vendor_id == kNintendoVendorId &&
         (product_id == kWiiRemoteProductId || product_id == kWiiRemoteTrProductId);
}

//! The udev rule that gives the user of the active seat session (the kiosk's) the remote's
//! hidraw node. The package ships it (kUdevRulePath); without the package the operator
//! creates kLocalUdevRulePath by hand. A Bluetooth remote's hidraw node hangs under a HID
//! device named BUS:VENDOR:PRODUCT.N (hex, upper case, e.g. 0005:057E:0306.0003) and has no
//! USB idVendor/idProduct attributes, so the rule matches that name (which also covers a
//! USB HID device with the same ids).
inline constexpr std::string_view kUdevRulePath = "/usr/lib/udev/rules.d/70-mallet-wiimote.rules";
inline constexpr std::string_view kLocalUdevRulePath = "/etc/udev/rules.d/70-mallet-wiimote.rules";
inline constexpr std::string_view kUdevRule =
    R"(KERNEL=="hidraw*", KERNELS=="*:057E:0306.*|*:057E:0330.*", TAG+="uaccess")";

//! The hint printed when a remote cannot be opened or none is seen: "the remote's
//! /dev/hidraw* node must be readable ...", naming the rule's file and content and how to
//! apply it (no final full stop, so callers can embed it).
std::string udev_hint();

//! One HID device as enumeration reports it.
struct HidDeviceInfo {
  std::string path;  //!< e.g. /dev/hidraw3
  std::uint16_t vendor_id = 0;
  std::uint16_t product_id = 0;
  std::string serial;   //!< on Linux/Bluetooth: the remote's address, e.g. 00:1f:32:aa:bb:cc
  std::string product;  //!< e.g. "Nintendo RVL-CNT-01"
  friend bool operator==(const HidDeviceInfo&, const HidDeviceInfo&) = default;
};

//! "RVL-CNT-01" / "RVL-CNT-01-TR" for the two product ids, else "0xPPPP".
std::string product_name(std::uint16_t product_id);

//! True when `filter` is empty or a substring of the device's path or serial
//! (case-insensitive): how the operator names one remote among several.
bool matches_device(const HidDeviceInfo& device, std::string_view filter);
//! The first of `devices` that matches `filter` (matches_device), or nothing.
std::optional<HidDeviceInfo> first_matching(const std::vector<HidDeviceInfo>& devices, std::string_view filter);
//! A remote's identity in a calibration file and the logs: its Bluetooth address, else its
//! hidraw path.
std::string remote_identity(const HidDeviceInfo& device);

//! An open device. Used by one thread at a time (the device's reading thread).
class Transport {
 public:
  virtual ~Transport() = default;
  //! Sends one output report, byte 0 = report id. False when the device is gone.
  virtual bool write(std::span<const std::uint8_t> report) = 0;
  //! Waits up to `timeout_ms` for one input report and copies it into `buffer` (byte 0 =
  //! report id): > 0 its length, 0 time-out, -1 the device is gone.
  virtual int read(std::span<std::uint8_t> buffer, int timeout_ms) = 0;
};

//! A transport, or why the device could not be opened (one line, with the udev hint
//! when the cause may be permissions).
struct OpenResult {
  std::unique_ptr<Transport> transport;
  std::string error;
};

//! Finds and opens remotes.
class DeviceFinder {
 public:
  virtual ~DeviceFinder() = default;
  //! The Wii Remotes present now (vendor 0x057e, products 0x0306 and 0x0330 only).
  virtual std::vector<HidDeviceInfo> enumerate() = 0;
  virtual OpenResult open(const std::string& path) = 0;
};

}  // namespace mallet::input::wiimote
