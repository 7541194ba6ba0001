#include "app/kiosk/language_check.hpp"

#include <algorithm>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "core/catalogue_file.hpp"
#include "core/data_paths.hpp"
#include "core/visitor_catalogues.hpp"
#include "core/visitor_language.hpp"
#include "render/font_atlas.hpp"

namespace mallet::app {
namespace {

constexpr std::size_t kNamed = 3;  // texts named of those missing; the rest counted

//! What one language lacks, in words ("" if nothing).
struct Lacks {
  std::string problem;    //!< its catalogue does not read
  std::vector<std::string> texts;  //!< msgids without a translation
  std::string letters;             //!< letters no font of the language has, each once
  std::string font;                //!< the family its text starts with
};

Lacks lacks_of(const std::string& language, const Catalogue& all, const render::FontAtlas& atlas) {
  Lacks out;
  std::vector<std::string> problems;
  Catalogue texts;
  if (const std::filesystem::path dropped = dropin_catalogue(language); !dropped.empty())
    texts = read_catalogue(dropped, problems);
  std::error_code ec;
  if (const std::filesystem::path shipped = locale_dir() / language / "LC_MESSAGES" / "mallet.mo";
      is_visitor_language(language) && std::filesystem::exists(shipped, ec)) {
    const Catalogue s = read_catalogue(shipped, problems);
    texts.texts.insert(s.texts.begin(), s.texts.end());  // a drop-in's own come first
  }
  if (!problems.empty()) out.problem = problems.front();
  std::set<std::string> seen;
  for (const std::string& id : all.msgids) {
    const auto it = texts.texts.find(id);
    if (it == texts.texts.end()) {
      out.texts.push_back(id);
      continue;
    }
    for (const std::string& letter : atlas.missing_letters(language, it->second, 1000))
      if (seen.insert(letter).second)  // as written, and its code point (a letter may not show where it is read)
        out.letters += (out.letters.empty() ? "" : ", ") + letter +
                       fmt::format(" (U+{:04X})", static_cast<std::uint32_t>(render::decode_utf8(letter).at(0)));
  }
  out.font = atlas.fonts(language).faces().front()->family();
  return out;
}

std::string quoted_list(const std::vector<std::string>& texts) {
  std::string out;
  for (std::size_t i = 0; i < texts.size() && i < kNamed; ++i) out += (i ? ", \"" : "\"") + texts[i] + "\"";
  if (texts.size() > kNamed) out += " and " + std::to_string(texts.size() - kNamed) + " more";
  return out;
}

}  // namespace

std::filesystem::path text_template() { return data_dir() / "po" / "mallet.pot"; }

DoctorCheck check_language(const AppConfig& config) {
  std::vector<std::string> shown{config.language};
  for (const std::string& l : config.attract.languages)
    if (std::find(shown.begin(), shown.end(), l) == shown.end()) shown.push_back(l);
  std::vector<std::string> problems;
  const Catalogue all = read_catalogue(text_template(), problems);
  if (all.msgids.empty())
    return {"language", CheckLevel::warn, "the template of the texts cannot be read: " + (problems.empty() ? text_template().string() : problems.front()),
            "reinstall the package (it ships " + text_template().string() + ")"};
  const render::FontAtlas atlas(24.0f, [&] {
    render::FontChoice c;
    for (const auto& [l, f] : config.render.fonts) c.families.emplace(l, f);
    return c;
  }());
  std::string found, fix;
  CheckLevel level = CheckLevel::ok;
  for (const std::string& language : shown) {
    if (!found.empty()) found += "; ";
    if (language == "en") {
      found += "en: the texts as written";
      continue;
    }
    Lacks lacks;
    try {
      lacks = lacks_of(language, all, atlas);
    } catch (const std::exception& e) {
      lacks.problem = e.what();
    }
    const std::size_t translated = all.msgids.size() - lacks.texts.size();
    found += language + ": " + std::to_string(translated) + " of " + std::to_string(all.msgids.size()) + " texts";
    if (!lacks.font.empty()) found += " in " + lacks.font;
    if (!lacks.problem.empty()) {
      level = CheckLevel::warn;
      found += " (" + lacks.problem + ")";
    }
    if (!lacks.texts.empty()) {
      level = CheckLevel::warn;
      found += ", untranslated: " + quoted_list(lacks.texts) + " (shown in English)";
      fix += (fix.empty() ? "" : "; ") + std::string("translate them in ") +
             (dropin_catalogue(language).empty() ? (dropin_locale_dir() / (language + ".po")).string()
                                                  : dropin_catalogue(language).string());
    }
    if (!lacks.letters.empty()) {
      level = CheckLevel::warn;
      found += ", no font has: " + lacks.letters;
      fix += (fix.empty() ? "" : "; ") + std::string("install a font with those letters, and name its family in [fonts] ") +
             language + " = \"...\"";
    }
  }
  return {"language", level, found, fix};
}

}  // namespace mallet::app
