#pragma once
// The visitor languages' catalogues on this machine (core/visitor_language.hpp looks the
// texts up in them), and starting the kiosk's language from the settings.
//
// locale_dir(): $MALLET_LOCALE_DIR; else <prefix>/share/locale for an installed binary
// (<prefix>/share/mallet holds its data: /usr/share/locale for the package); else the
// catalogues this build made (<build>/locale); else /usr/share/locale.
#include <filesystem>
#include <string>
#include <vector>

namespace mallet {

std::filesystem::path locale_dir();

//! gettext bound to locale_dir(), the drop-in folder read, showing `language` (the settings
//! checked it is offered). A catalogue that is missing or unreadable, or a missing locale,
//! adds a line to `problems`: its texts show in English, and the kiosk goes on.
void start_visitor_language(const std::string& language, std::vector<std::string>& problems);

}  // namespace mallet
