#include "core/catalogue_file.hpp"

#include <algorithm>
#include <csetjmp>
#include <cstdint>
#include <fstream>
#include <iterator>

#include <gettext-po.h>

#include "core/file_error.hpp"

namespace mallet {
namespace {

std::uint32_t word(const std::string& b, std::size_t at, bool swapped) {
  const auto u = [&](std::size_t i) { return std::uint32_t{static_cast<unsigned char>(b[at + i])}; };
  return swapped ? (u(0) << 24) | (u(1) << 16) | (u(2) << 8) | u(3) : (u(3) << 24) | (u(2) << 16) | (u(1) << 8) | u(0);
}

//! One problem as one line: FileError's form, with a control character quoted from the file
//! (a msgid's newline, a parser's message) written as an escape.
std::string problem_line(const std::string& file, std::uint32_t line, std::uint32_t column, const std::string& why) {
  return FileError(file, line, column, why).what();
}

bool is_mo(const std::string& b) {
  if (b.size() < 4) return false;
  const std::uint32_t magic = word(b, 0, false);
  return magic == 0x950412deu || magic == 0xde120495u;
}

//! A .mo file: a header of 32-bit words in the writer's byte order, then tables of (length,
//! offset) pairs. Every length and offset is checked against the file.
void read_mo(const std::string& name, const std::string& b, Catalogue& out, std::vector<std::string>& problems) {
  const auto fail = [&](std::size_t at, const std::string& why) {
    problems.push_back(problem_line(name, 0, 0, "byte " + std::to_string(at) + ": " + why));
    out = {};
    out.read = false;
  };
  if (b.size() < 28) return fail(0, "too short for a gettext catalogue's header");
  if (!is_mo(b)) return fail(0, "not a gettext catalogue (.mo): wrong magic number");
  const bool swapped = word(b, 0, false) == 0xde120495u;
  const std::uint64_t count = word(b, 8, swapped), originals = word(b, 12, swapped), table = word(b, 16, swapped);
  if (originals + count * 8 > b.size()) return fail(12, "its table of texts runs past the end of the file");
  if (table + count * 8 > b.size()) return fail(16, "its translation table runs past the end of the file");
  for (std::uint64_t i = 0; i < count; ++i) {
    const auto at_id = static_cast<std::size_t>(originals + i * 8), at_str = static_cast<std::size_t>(table + i * 8);
    const std::uint64_t id_length = word(b, at_id, swapped), id_offset = word(b, at_id + 4, swapped);
    const std::uint64_t length = word(b, at_str, swapped), offset = word(b, at_str + 4, swapped);
    if (id_offset + id_length > b.size()) return fail(at_id, "a text runs past the end of the file");
    if (offset + length > b.size()) return fail(at_str, "a translation runs past the end of the file");
    if (id_length == 0) continue;  // msgid "": the header
    // A plural entry holds its forms NUL-separated: the singular is the text.
    std::string id = b.substr(static_cast<std::size_t>(id_offset), static_cast<std::size_t>(id_length));
    std::string str = b.substr(static_cast<std::size_t>(offset), static_cast<std::size_t>(length));
    id.resize(id.find('\0') == std::string::npos ? id.size() : id.find('\0'));
    str.resize(str.find('\0') == std::string::npos ? str.size() : str.find('\0'));
    out.msgids.push_back(id);
    if (!str.empty()) out.texts.emplace(std::move(id), std::move(str));
  }
}

// libgettextpo reports through callbacks, and one that reports a fatal error must not
// return: it jumps back to read_po, which then gives up on the file. Only C frames lie in
// between (libgettextpo's), so nothing is left half-destroyed.
thread_local std::jmp_buf* po_escape = nullptr;
thread_local std::vector<std::string>* po_problems = nullptr;
thread_local const std::string* po_name = nullptr;
thread_local bool po_failed = false;

void po_error(int severity, po_message_t, const char* filename, std::size_t line, std::size_t column, int,
              const char* text) {
  const bool placed = filename && line != static_cast<std::size_t>(-1);
  const auto place = [](std::size_t n) { return static_cast<std::uint32_t>(std::min<std::size_t>(n, UINT32_MAX)); };
  const std::uint32_t at_line = placed ? place(line) : 0;
  const std::uint32_t at_column = placed && column != static_cast<std::size_t>(-1) ? place(column) : 0;
  std::string message = text ? text : "unreadable";
  while (!message.empty() && message.back() == '\n') message.pop_back();
  for (char& c : message)
    if (c == '\n') c = ' ';
  // The closing "found N fatal errors" repeats the errors said: not a problem of its own.
  if (severity == PO_SEVERITY_ERROR || (severity == PO_SEVERITY_FATAL_ERROR && !po_failed))
    po_problems->push_back(problem_line(filename ? filename : *po_name, at_line, at_column, message));
  if (severity != PO_SEVERITY_WARNING) po_failed = true;
  if (severity == PO_SEVERITY_FATAL_ERROR) std::longjmp(*po_escape, 1);
}

void po_error2(int severity, po_message_t m1, const char* f1, std::size_t l1, std::size_t c1, int ml1, const char* t1,
               po_message_t, const char*, std::size_t, std::size_t, int, const char*) {
  po_error(severity, m1, f1, l1, c1, ml1, t1);
}

void read_po(const std::string& name, Catalogue& out, std::vector<std::string>& problems) {
  static const po_xerror_handler handler{po_error, po_error2};
  std::jmp_buf escape;
  po_escape = &escape;
  po_problems = &problems;
  po_name = &name;
  po_failed = false;
  po_file_t file = nullptr;
  if (setjmp(escape) != 0) {  // a fatal error: the file does not read
    out = {};
    out.read = false;
    return;
  }
  file = po_file_read(name.c_str(), &handler);
  if (!file) return;
  po_message_iterator_t it = po_message_iterator(file, nullptr);
  for (po_message_t m = po_next_message(it); m; m = po_next_message(it)) {
    if (po_message_is_obsolete(m)) continue;
    const std::string id = po_message_msgid(m);
    if (id.empty()) continue;  // the header
    out.msgids.push_back(id);
    const std::string str = po_message_msgstr(m);
    if (!str.empty() && !po_message_is_fuzzy(m)) out.texts.emplace(id, str);
  }
  po_message_iterator_free(it);
  po_file_free(file);
  if (po_failed) out.read = false;
}

}  // namespace

// What LeakSanitizer (the asan and fuzz builds) is told not to report, each known and bounded:
// libgettextpo keeps what it parsed of a file whose fatal error ended the parse (read_po
// jumps out of it), one file's worth per reading of a broken drop-in; fontconfig's
// configuration (render/font_fallback) lives as long as the process, as fontconfig intends.
#if defined(__SANITIZE_ADDRESS__)
#define MALLET_LSAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define MALLET_LSAN 1
#endif
#endif
#ifdef MALLET_LSAN
extern "C" const char* __lsan_default_suppressions() { return "leak:libgettextpo.so\nleak:libfontconfig.so\n"; }
// Quietly: a command's output (`mallet doctor`'s lines) stays its own.
extern "C" const char* __lsan_default_options() { return "print_suppressions=0"; }
#endif

std::string printf_conversions(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '%') continue;
    std::size_t j = i + 1;
    if (j < text.size() && text[j] == '%') {
      i = j;
      continue;
    }
    while (j < text.size() && std::string_view("-+ #0123456789.*'").find(text[j]) != std::string_view::npos) ++j;
    while (j < text.size() && std::string_view("hlLqjzt").find(text[j]) != std::string_view::npos) out += text[j++];
    if (j < text.size()) out += text[j];
    i = j;
  }
  return out;
}

Catalogue read_catalogue(const std::filesystem::path& file, std::vector<std::string>& problems) {
  Catalogue out;
  const std::string name = file.string();
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    problems.push_back(problem_line(name, 0, 0, "cannot open the catalogue"));
    out.read = false;
    return out;
  }
  const std::string bytes{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (file.extension() == ".mo" || is_mo(bytes))
    read_mo(name, bytes, out, problems);
  else
    read_po(name, out, problems);
  for (auto it = out.texts.begin(); it != out.texts.end();) {
    if (printf_conversions(it->first) != printf_conversions(it->second)) {
      problems.push_back(problem_line(name, 0, 0,
                                      "the translation of \"" + it->first + "\" has other printf directives than the text (\"" +
                                          printf_conversions(it->second) + "\" instead of \"" +
                                          printf_conversions(it->first) + "\"): shown in English"));
      it = out.texts.erase(it);
    } else {
      ++it;
    }
  }
  return out;
}

}  // namespace mallet
