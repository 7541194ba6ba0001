// `mallet config show`: the settings as the kiosk would read them now, merged from the
// settings file and its drop-ins, each key saying which file it came from.
#include <cstdio>
#include <memory>

#include "app/cli/commands.hpp"
#include "core/data_paths.hpp"
#include "app/common/settings_source.hpp"

namespace mallet::app {

namespace {
struct ConfigShowOptions {
  std::optional<std::filesystem::path> config = default_settings();
  std::optional<std::filesystem::path> config_dir;
};
}  // namespace

void register_config(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("config", "The kiosk's settings: show them merged with their drop-ins");
  cmd->require_subcommand(1);
  auto o = std::make_shared<ConfigShowOptions>();
  CLI::App* show = cmd->add_subcommand("show", "Print the merged settings, each key with the file it came from");
  show->footer(R"(Reads the settings file (default: the operator's mallet.toml, /etc/mallet/mallet.toml when
installed) and merges the drop-ins of --config-dir over it (default: the file's name + .d,
/etc/mallet/mallet.toml.d): every *.toml there, in lexical order of the names, key by key
(a table merges, any other value - an array too - is replaced). Prints the merged TOML on
stdout, each key followed by `# from FILE:LINE`; keys no file sets keep their built-in
defaults and are not listed. A drop-in that cannot be read or whose values are refused is
left out, with FILE:LINE: problem on stderr, as the kiosk leaves it out.
Exit status: 0; 2 when the settings file or a drop-in was refused.)");
  add_settings_options(*show, o->config, o->config_dir);
  show->callback([o] {
    const config::LoadedSettings s = operator_settings(o->config, o->config_dir);
    for (const std::string& r : s.refused) std::fprintf(stderr, "mallet config show: refused: %s\n", r.c_str());
    std::fputs(config::show_settings(s).c_str(), stdout);
    if (!s.refused.empty()) finish_with(2);
  });
}

}  // namespace mallet::app
