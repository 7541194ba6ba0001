// Every Wii Remote input-report parser on arbitrary bytes: no crash, no sanitizer report,
// and the parsers agree with each other.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <span>
#include <string>
#include <variant>

#include "input/wiimote/ir_startup.hpp"
#include "input/wiimote/reports.hpp"

namespace wm = mallet::input::wiimote;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::span<const std::uint8_t> bytes(data, size);
  const auto any = wm::parse_input(bytes);
  const auto ir = wm::parse_ir(bytes);
  const auto status = wm::parse_status(bytes);
  const auto read = wm::parse_read_data(bytes);
  const auto ack = wm::parse_ack(bytes);
  if (!any) (void)any.error().message();
  // parse_input succeeds exactly when the id is known and the length is that id's.
  const bool known_size = size > 0 && wm::input_report_size(data[0]) == size;
  if (any.has_value() != known_size) std::abort();
  if (ir.has_value()) {
    if (!any.has_value() || !std::holds_alternative<wm::IrReport>(*any)) std::abort();
    for (const auto& slot : ir->slots) {
      if (!slot) continue;
      if (slot->x < 0 || slot->x > wm::kIrMaxX || slot->y < 0 || slot->y > wm::kIrMaxY) std::abort();
      if (slot->size < -1 || slot->size > 15) std::abort();
      if ((slot->size == -1) != (ir->format == wm::IrFormat::basic)) std::abort();
    }
  }
  if (status.has_value() && !std::holds_alternative<wm::StatusReport>(*any)) std::abort();
  if (read.has_value() && (read->size < 1 || read->size > 16)) std::abort();
  if (ack.has_value() && !std::holds_alternative<wm::AckReport>(*any)) std::abort();

  // The start-up state machine eats the same bytes without trouble.
  wm::IrStartup startup;
  startup.start(0);
  startup.feed(bytes, 1);
  startup.tick(size > 0 ? static_cast<mallet::Nanos>(data[0]) * 1'000'000 : 0);
  while (startup.poll()) {
  }

  // And the hex reader on the same bytes as text.
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  if (const auto parsed = wm::parse_hex_bytes(text)) {
    const auto again = wm::parse_hex_bytes(wm::to_hex(*parsed));
    if (!again || *again != *parsed) std::abort();
  } else if (parsed.error().column < 1 || parsed.error().column > size) {
    std::abort();
  }
  return 0;
}
