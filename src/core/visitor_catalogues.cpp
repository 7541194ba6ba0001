#include "core/visitor_catalogues.hpp"

#include <cstdio>
#include <cstdlib>
#include <system_error>

#include "core/data_paths.hpp"
#include "core/visitor_language.hpp"

#ifndef MALLET_BUILD_LOCALE_DIR
#define MALLET_BUILD_LOCALE_DIR ""
#endif

namespace mallet {

std::filesystem::path locale_dir() {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (const char* env = std::getenv("MALLET_LOCALE_DIR"); env && *env) return env;
  if (const fs::path prefix = executable_prefix();
      !prefix.empty() && fs::exists(prefix / "share" / "mallet" / "config" / "materials.toml", ec))
    return prefix / "share" / "locale";
  if (const fs::path built = MALLET_BUILD_LOCALE_DIR; !built.empty() && fs::is_directory(built, ec)) return built;
  return "/usr/share/locale";
}

void start_visitor_language(const std::string& language, std::vector<std::string>& problems) {
  bind_visitor_catalogues(locale_dir());
  std::vector<std::string> shipped;
  catalogue_texts(locale_dir(), shipped);
  for (const std::string& p : shipped) problems.push_back("language: " + p);
  for (const std::string& p : load_dropin_catalogues()) problems.push_back("language: " + p);
  use_visitor_language(language);
}

}  // namespace mallet
