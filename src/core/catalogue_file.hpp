#pragma once
// A gettext catalogue read into memory: a compiled one (.mo: the GNU gettext manual, "The
// Format of GNU MO Files") by the reader here, a translator's source (.po, or the template
// mallet.pot) by GNU gettext's own library, libgettextpo. What an operator drops in to add a
// language (core/visitor_language.hpp), and what `mallet doctor` checks a language against.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace mallet {

struct Catalogue {
  //! msgid → its translation; an untranslated or fuzzy entry is absent, as gettext would show
  //! it (in English). The header (msgid "") is not an entry.
  std::map<std::string, std::string, std::less<>> texts;
  std::vector<std::string> msgids;  //!< every msgid the file has, translated or not, in file order
  bool read = true;  //!< false: the file does not read (its problems say where); what was read is kept
};

//! Reads `file` (.mo by its name or its magic number, else .po). Each problem adds one line to `problems`
//! naming the file and the place ("FILE:LINE:COLUMN: ..." or "FILE: byte N: ..."): a file that
//! does not read gives an empty catalogue; an entry whose translation's printf directives
//! differ from its msgid's (which would print the wrong thing, or crash) is left out.
Catalogue read_catalogue(const std::filesystem::path& file, std::vector<std::string>& problems);

//! The printf conversions of a text in order ("%s", "%.1f" → "sf"; "%%" is none).
std::string printf_conversions(const std::string& text);

}  // namespace mallet
