#pragma once
// The visitor's language. Every text a visitor or an operator reads on the screen is looked
// up in the "mallet" domain's catalogue of the language: po/<lang>.po compiled by Debian's
// msgfmt into <locale>/<lang>/LC_MESSAGES/mallet.mo, read by core/catalogue_file (the reader
// of the operators' drop-ins too), not by glibc's gettext, whose answer depends on the
// process's locale (glibc 2.39 and later ignore LANGUAGE under C.UTF-8: Debian 13).
// English is the texts as written in the code (the msgids): it needs no catalogue.
//
// Marking: tr("text") translates where it stands; N_("text") only marks a text that is
// translated later (xgettext takes both keywords, see po/CMakeLists.txt).
//
// The language is the process's: bind, use and tr belong to the main thread (the one that
// draws the text). A language can be switched at any time (the operator page, the
// attract mode's cycle); the next tr() answers in it.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#define N_(text) text

namespace mallet {

//! "en" first, then each language with a catalogue (po/LINGUAS), in that file's order, then
//! each one an operator dropped in (below), by name. A copy: reading the drop-in folder again
//! (a reload) changes the list while a caller may still be going through the last one.
std::vector<std::string> visitor_languages();
//! A language's code: two or three lowercase letters (ISO 639: "ar", "yue").
bool is_language_code(std::string_view code);

// A language added without rebuilding: an operator drops its catalogue into
// dropin_locale_dir() as xx.po (a translator's file, read by GNU gettext's libgettextpo),
// xx.mo or xx/LC_MESSAGES/mallet.mo (compiled by msgfmt), and sets [kiosk] language = "xx".
// A catalogue there for a shipped language replaces the shipped texts it translates. A text
// it lacks shows as shipped (in English for a new language); `mallet doctor` names each.

//! /etc/mallet/locale; $MALLET_LOCALE_DROPIN instead (the tests).
std::filesystem::path dropin_locale_dir();
//! Reads dropin_locale_dir() again (the first use of the languages reads it; the settings'
//! checks read it again for a language they do not know). Returns its problems, one line each
//! naming the file and the place; a catalogue that does not read is not offered.
const std::vector<std::string>& load_dropin_catalogues();
const std::vector<std::string>& dropin_problems();  //!< the last read's
//! The file a dropped-in language was read from; empty: none dropped in for it.
std::filesystem::path dropin_catalogue(std::string_view language);
bool is_visitor_language(std::string_view language);
//! "en, de, fr, ja": for messages that list what is allowed.
std::string visitor_languages_text();

//! Takes the shipped catalogues from <locale_dir>/<lang>/LC_MESSAGES/mallet.mo (each read
//! the first time its language is shown) and shows English. Needs no locale.
void bind_visitor_catalogues(const std::filesystem::path& locale_dir);

//! Every later tr() answers in `language` (one of visitor_languages(); another shows English).
void use_visitor_language(std::string_view language);
const std::string& visitor_language();  //!< the one in use; "en" before any use

//! `msgid` in the visitor's language: its translation (a dropped-in catalogue's first, then
//! the shipped one's), or `msgid` itself (English, a text a catalogue lacks, or no catalogue
//! bound). The pointer stays valid for the process.
const char* tr(const char* msgid);

//! The translations in <locale_dir>'s catalogues for every shipped language, one after the
//! other (UTF-8, a line each). A catalogue that is missing or malformed adds a line to
//! `problems` ("FILE: byte N: ...").
std::string catalogue_texts(const std::filesystem::path& locale_dir, std::vector<std::string>& problems);

}  // namespace mallet
