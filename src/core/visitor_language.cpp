#include "core/visitor_language.hpp"

#include <libintl.h>

#include <algorithm>
#include <clocale>
#include <cstdlib>
#include <map>
#include <memory>
#include <sstream>
#include <utility>

#include "core/catalogue_file.hpp"

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

//! A language an operator dropped in: its texts, read from its file.
struct Dropped {
  std::string language;
  std::filesystem::path file;
  Catalogue catalogue;
};

//! The drop-in folder's languages as last read. A catalogue read before and since changed or
//! removed is kept (never freed): tr() hands out pointers into it for the process. One read
//! again unchanged is the same object, so reloads alone never grow what is kept.
struct DropIns {
  std::vector<std::shared_ptr<const Dropped>> now;
  std::vector<std::shared_ptr<const Dropped>> kept;
  std::vector<std::string> problems;
  std::vector<std::string> languages{"en"};  //!< shipped, then dropped in
  bool read = false;
};

DropIns& drop_ins() {
  static DropIns d;
  return d;
}

std::vector<std::string> shipped_languages() {
  std::vector<std::string> v{"en"};
  std::istringstream in(MALLET_CATALOGUE_LANGUAGES);
  for (std::string l; in >> l;) v.push_back(l);
  return v;
}

//! The drop-in file of a language in `dir`: xx/LC_MESSAGES/mallet.mo, xx.mo or xx.po, in that
//! order of preference (a compiled catalogue over its source).
std::vector<std::pair<std::string, std::filesystem::path>> dropped_files(const std::filesystem::path& dir) {
  namespace fs = std::filesystem;
  std::map<std::string, fs::path> found;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const fs::path p = it->path();
    const std::string stem = p.stem().string();
    std::error_code e2;
    if (it->is_directory(e2) && is_language_code(p.filename().string()) &&
        fs::is_regular_file(p / "LC_MESSAGES" / "mallet.mo", e2))
      found[p.filename().string()] = p / "LC_MESSAGES" / "mallet.mo";
    else if (p.extension() == ".mo" && is_language_code(stem) && !found.count(stem))
      found[stem] = p;
    else if (p.extension() == ".po" && is_language_code(stem) && !found.count(stem))
      found[stem] = p;
  }
  for (auto& [language, file] : found)  // a compiled catalogue wins over its .po beside it
    if (file.extension() == ".po") {
      if (fs::is_regular_file(dir / (language + ".mo"), ec)) file = dir / (language + ".mo");
    }
  return {found.begin(), found.end()};
}

const Dropped* dropped(std::string_view language) {
  for (const auto& d : drop_ins().now)
    if (d->language == language) return d.get();
  return nullptr;
}

}  // namespace

bool is_language_code(std::string_view code) {
  if (code.size() < 2 || code.size() > 3) return false;
  for (const char c : code)
    if (c < 'a' || c > 'z') return false;
  return true;
}

std::filesystem::path dropin_locale_dir() {
  if (const char* env = std::getenv("MALLET_LOCALE_DROPIN"); env && *env) return env;
  return "/etc/mallet/locale";
}

const std::vector<std::string>& load_dropin_catalogues() {
  DropIns& d = drop_ins();
  d.read = true;
  d.problems.clear();
  std::vector<std::shared_ptr<const Dropped>> before = std::move(d.now);
  d.now.clear();
  d.languages = shipped_languages();
  for (const auto& [language, file] : dropped_files(dropin_locale_dir())) {
    auto one = std::make_shared<Dropped>();
    one->language = language;
    one->file = file;
    one->catalogue = read_catalogue(file, d.problems);
    if (!one->catalogue.read) continue;  // it does not read: not offered
    if (!is_visitor_language(language)) d.languages.push_back(language);
    // The same texts as before: the catalogue read before goes on (nothing grows reload by reload).
    const auto same = std::find_if(before.begin(), before.end(), [&](const auto& b) {
      return b && b->language == one->language && b->catalogue.texts == one->catalogue.texts;
    });
    if (same != before.end()) {
      d.now.push_back(std::move(*same));
      continue;
    }
    d.now.push_back(std::move(one));
  }
  for (auto& old : before)  // changed or gone: kept, for the texts tr() handed out
    if (old) d.kept.push_back(std::move(old));
  return d.problems;
}

const std::vector<std::string>& dropin_problems() {
  if (!drop_ins().read) load_dropin_catalogues();
  return drop_ins().problems;
}

std::filesystem::path dropin_catalogue(std::string_view language) {
  if (!drop_ins().read) load_dropin_catalogues();
  const Dropped* d = dropped(language);
  return d ? d->file : std::filesystem::path{};
}

std::vector<std::string> visitor_languages() {
  if (!drop_ins().read) load_dropin_catalogues();
  return drop_ins().languages;
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

const char* tr(const char* msgid) {
  if (const Dropped* d = dropped(current())) {
    const auto it = d->catalogue.texts.find(std::string_view(msgid));
    if (it != d->catalogue.texts.end()) return it->second.c_str();
  }
  return dgettext(kDomain, msgid);
}

std::string catalogue_texts(const std::filesystem::path& locale_dir, std::vector<std::string>& problems) {
  std::string texts;
  for (const std::string& l : shipped_languages()) {
    if (l == "en") continue;
    const std::size_t before = problems.size();
    const Catalogue c = read_catalogue(locale_dir / l / "LC_MESSAGES" / "mallet.mo", problems);
    if (problems.size() > before && c.msgids.empty() && problems.back().find("cannot open") != std::string::npos)
      problems.back() += " (build it: cmake --build)";
    for (const auto& [id, text] : c.texts) texts += text + '\n';
  }
  return texts;
}

}  // namespace mallet
