#include "core/visitor_language.hpp"

#include <libintl.h>

#include <clocale>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>

// glibc's libintl: bumping it makes every cached lookup stale, so that a changed LANGUAGE
// takes effect at the next gettext call (the GNU gettext manual, "Being a gettext grok").
extern "C" int _nl_msg_cat_cntr;  // NOLINT(bugprone-reserved-identifier)

#ifndef MALLET_CATALOGUE_LANGUAGES
#define MALLET_CATALOGUE_LANGUAGES ""
#endif

namespace mallet {
namespace {

constexpr const char* kDomain = "mallet";

std::string& current() {
  static std::string language = "en";
  return language;
}

std::uint32_t word(const std::string& b, std::size_t at, bool swapped) {
  const auto u = [&](std::size_t i) { return std::uint32_t{static_cast<unsigned char>(b[at + i])}; };
  return swapped ? (u(0) << 24) | (u(1) << 16) | (u(2) << 8) | u(3) : (u(3) << 24) | (u(2) << 16) | (u(1) << 8) | u(0);
}

//! The translated strings of one .mo file (the GNU gettext manual, "The Format of GNU MO
//! Files"): a header of 32-bit words in the writer's byte order, then tables of
//! (length, offset) pairs. Every length and offset is checked against the file.
std::string mo_translations(const std::filesystem::path& file, std::vector<std::string>& problems) {
  std::ifstream in(file, std::ios::binary);
  if (!in) {
    problems.push_back(file.string() + ": cannot open the catalogue (build it: cmake --build)");
    return {};
  }
  const std::string b{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  const auto fail = [&](std::size_t at, const std::string& why) {
    problems.push_back(file.string() + ": byte " + std::to_string(at) + ": " + why);
    return std::string{};
  };
  if (b.size() < 28) return fail(0, "too short for a gettext catalogue's header");
  const std::uint32_t magic = word(b, 0, false);
  const bool swapped = magic == 0xde120495u;
  if (magic != 0x950412deu && !swapped) return fail(0, "not a gettext catalogue (.mo): wrong magic number");
  const std::uint64_t count = word(b, 8, swapped), originals = word(b, 12, swapped), table = word(b, 16, swapped);
  if (originals + count * 8 > b.size()) return fail(12, "its table of texts runs past the end of the file");
  if (table + count * 8 > b.size()) return fail(16, "its translation table runs past the end of the file");
  std::string out;
  for (std::uint64_t i = 0; i < count; ++i) {
    const std::size_t entry = static_cast<std::size_t>(table + i * 8);
    const std::uint64_t length = word(b, entry, swapped), offset = word(b, entry + 4, swapped);
    if (offset + length > b.size()) return fail(entry, "a translation runs past the end of the file");
    if (word(b, static_cast<std::size_t>(originals + i * 8), swapped) == 0) continue;  // msgid "": the header
    out.append(b, offset, length);
    out.push_back('\n');
  }
  return out;
}

}  // namespace

const std::vector<std::string>& visitor_languages() {
  static const std::vector<std::string> languages = [] {
    std::vector<std::string> v{"en"};
    std::istringstream in(MALLET_CATALOGUE_LANGUAGES);
    for (std::string l; in >> l;) v.push_back(l);
    return v;
  }();
  return languages;
}

bool is_visitor_language(std::string_view language) {
  for (const std::string& l : visitor_languages())
    if (l == language) return true;
  return false;
}

std::string visitor_languages_text() {
  std::string text;
  for (const std::string& l : visitor_languages()) text += (text.empty() ? "" : ", ") + l;
  return text;
}

std::string bind_visitor_catalogues(const std::filesystem::path& locale_dir) {
  bindtextdomain(kDomain, locale_dir.c_str());
  bind_textdomain_codeset(kDomain, "UTF-8");
  // gettext ignores LANGUAGE under the "C" locale; C.UTF-8 is built into glibc >= 2.35 and
  // needs no generated locale. Only LC_MESSAGES changes: numbers keep reading with '.'.
  const bool ok = std::setlocale(LC_MESSAGES, "C.UTF-8") != nullptr;
  use_visitor_language("en");
  return ok ? "" : "the C.UTF-8 locale is missing: every text is shown in English";
}

void use_visitor_language(std::string_view language) {
  current() = is_visitor_language(language) ? std::string(language) : "en";
  setenv("LANGUAGE", current().c_str(), 1);
  ++_nl_msg_cat_cntr;
}

const std::string& visitor_language() { return current(); }

const char* tr(const char* msgid) { return dgettext(kDomain, msgid); }

std::string catalogue_texts(const std::filesystem::path& locale_dir, std::vector<std::string>& problems) {
  std::string texts;
  for (const std::string& l : visitor_languages())
    if (l != "en") texts += mo_translations(locale_dir / l / "LC_MESSAGES" / "mallet.mo", problems);
  return texts;
}

}  // namespace mallet
