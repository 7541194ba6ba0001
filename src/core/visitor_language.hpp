#pragma once
// The visitor's language. Every text a visitor or an operator reads on the screen is looked
// up by gettext (glibc's libintl) in the "mallet" domain: one catalogue per language,
// po/<lang>.po compiled by Debian's msgfmt into <locale>/<lang>/LC_MESSAGES/mallet.mo.
// English is the texts as written in the code (the msgids): it needs no catalogue.
//
// Marking: tr("text") translates where it stands; N_("text") only marks a text that is
// translated later (xgettext takes both keywords, see po/CMakeLists.txt).
//
// gettext's language is the process's: bind, use and tr belong to the main thread (the one
// that draws the text). A language can be switched at any time (the operator page, the
// attract mode's cycle); the next tr() answers in it.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#define N_(text) text

namespace mallet {

//! "en" first, then each language with a catalogue (po/LINGUAS), in that file's order.
const std::vector<std::string>& visitor_languages();
bool is_visitor_language(std::string_view language);
//! "en, de, fr, ja": for messages that list what is allowed.
std::string visitor_languages_text();

//! Points gettext at <locale_dir>/<lang>/LC_MESSAGES/mallet.mo and shows English. Returns
//! a problem to report ("" if none): the C.UTF-8 locale gettext needs is missing.
std::string bind_visitor_catalogues(const std::filesystem::path& locale_dir);

//! Every later tr() answers in `language` (one of visitor_languages(); another shows English).
void use_visitor_language(std::string_view language);
const std::string& visitor_language();  //!< the one in use; "en" before any use

//! `msgid` in the visitor's language: its translation, or `msgid` itself (English, a text
//! a catalogue lacks, or no catalogue bound). The pointer stays valid for the process.
const char* tr(const char* msgid);

//! The translations in <locale_dir>'s catalogues for every shipped language, one after the
//! other (UTF-8), so that a font can bake every glyph they need before the first frame.
//! A catalogue that is missing or malformed adds a line to `problems` ("FILE: byte N: ...").
std::string catalogue_texts(const std::filesystem::path& locale_dir, std::vector<std::string>& problems);

}  // namespace mallet
