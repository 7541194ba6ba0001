// A language catalogue an operator drops in (core/catalogue_file.hpp) on arbitrary bytes, read
// as the kiosk reads /etc/mallet/locale: as a .po (libgettextpo) when the input's first byte
// is odd ('#', 'm' of a translator's file), else as a .mo (our reader; 0xde of its magic). Every problem is one line naming the file; every
// translation kept has its text's printf directives; nothing crashes, hangs or leaks.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "core/catalogue_file.hpp"
#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const bool mo = size == 0 || (data[0] & 1) == 0;
  const std::filesystem::path path =
      mallet::fuzz::scratch().write(mo ? "xx.mo" : "xx.po", mallet::fuzz::text_of(data, size));
  const std::string name = path.string();
  std::vector<std::string> problems;
  const mallet::Catalogue c = mallet::read_catalogue(path, problems);
  for (const std::string& p : problems)
    if (p.substr(0, name.size()) != name || p.find_first_of("\n\r") != std::string::npos) std::abort();
  for (const auto& [id, text] : c.texts)
    if (mallet::printf_conversions(id) != mallet::printf_conversions(text) || text.empty()) std::abort();
  if (c.texts.size() > c.msgids.size()) std::abort();
  return 0;
}
