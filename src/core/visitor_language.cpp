#include "core/visitor_language.hpp"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <memory>
#include <sstream>
#include <utility>

#include "core/catalogue_file.hpp"

#ifndef MALLET_CATALOGUE_LANGUAGES
#define MALLET_CATALOGUE_LANGUAGES ""
#endif

namespace mallet {
namespace {

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

//! The shipped catalogues, read by read_catalogue (the drop-ins' reader) from the folder
//! bind_visitor_catalogues named, each the first time its language is shown. Never freed:
//! tr() hands out pointers into them. glibc's gettext is not used: since glibc 2.39 (Debian
//! 13) it ignores LANGUAGE under the C.UTF-8 locale, and every text came back in English.
struct Shipped {
  std::filesystem::path locale_dir;
  std::map<std::string, std::unique_ptr<const Catalogue>, std::less<>> read;  //!< by language
};

Shipped& shipped() {
  static Shipped s;
  return s;
}

const Catalogue* shipped_catalogue(const std::string& language) {
  Shipped& s = shipped();
  if (s.locale_dir.empty() || language == "en") return nullptr;
  auto it = s.read.find(language);
  if (it == s.read.end()) {
    // Its problems are the startup's to report (catalogue_texts reads every one of them).
    std::vector<std::string> problems;
    auto c = std::make_unique<const Catalogue>(
        read_catalogue(s.locale_dir / language / "LC_MESSAGES" / "mallet.mo", problems));
    it = s.read.emplace(language, std::move(c)).first;
  }
  return it->second.get();
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

void bind_visitor_catalogues(const std::filesystem::path& locale_dir) {
  Shipped& s = shipped();
  if (s.locale_dir != locale_dir) {  // another folder: its catalogues are read anew (the old kept)
    static std::vector<std::unique_ptr<const Catalogue>> kept;
    for (auto& [language, c] : s.read) kept.push_back(std::move(c));
    s.read.clear();
    s.locale_dir = locale_dir;
  }
  use_visitor_language("en");
}

void use_visitor_language(std::string_view language) {
  current() = is_visitor_language(language) ? std::string(language) : "en";
}

const std::string& visitor_language() { return current(); }

const char* tr(const char* msgid) {
  if (const Dropped* d = dropped(current())) {
    const auto it = d->catalogue.texts.find(std::string_view(msgid));
    if (it != d->catalogue.texts.end()) return it->second.c_str();
  }
  if (const Catalogue* c = shipped_catalogue(current())) {
    const auto it = c->texts.find(std::string_view(msgid));
    if (it != c->texts.end()) return it->second.c_str();
  }
  return msgid;
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
