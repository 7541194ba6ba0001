#pragma once
// A scriptable stand-in for libhidapi-hidraw: fake_hidapi.cpp defines the hid_* functions
// HidTransport calls, and a test binary links it instead of the real library (the real
// hid_open_path crashes on anything but a hidraw node, so it cannot be pointed at a file).
// The test scripts devices to enumerate, open failures, reports to read, when a device
// vanishes, and whether it answers like a Wii Remote; it reads back every write.
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace fake_hidapi {

using Bytes = std::vector<unsigned char>;

struct Device {
  std::string path;
  unsigned short vendor_id = 0;
  unsigned short product_id = 0;
  std::wstring serial;
  std::wstring product;
};

//! Forgets every device, script, record and hook.
void reset();
//! Listed by hid_enumerate (filtered by its vendor/product arguments, 0 = any, as hidapi does).
void add_device(const Device& device);
//! hid_open_path(path) fails: errno = `error_number`, hid_error(NULL) = `message`.
void fail_open(const std::string& path, int error_number, const std::wstring& message);
//! The next hid_read_timeout calls on `path` return these, in order (before any answer).
void push_report(const std::string& path, Bytes report);
//! After `reads` more successful reads, reads and writes on `path` fail (-1): it is gone.
void gone_after_reads(const std::string& path, int reads);
//! Answer like a Wii Remote: a 0x22 ack for every write with the ack bit (0x02 of byte 1)
//! or to memory (0x16), a 0x20 status report for a status request (0x15).
void set_answers(const std::string& path, bool answers);
//! Every report written to `path`, as hid_write received it (byte 0 = report id).
std::vector<Bytes> writes(const std::string& path);
//! The (vendor_id, product_id) of every hid_enumerate call.
std::vector<std::pair<unsigned short, unsigned short>> enumerate_calls();
//! Devices open now, and hid_close calls so far.
int open_count();
int close_count();
//! Called after every hid_read_timeout with its time-out and result (the test's clock).
void set_read_hook(std::function<void(int timeout_ms, int result)> hook);

}  // namespace fake_hidapi
