// [metrics] in the kiosk's settings: off by default (as shipped), a relative file is next to
// the settings file, and a bad value is refused with its file and line.
#include <gtest/gtest.h>

#include "core/config/app_config_loader.hpp"
#include "core/file_error.hpp"
#include "test_paths.hpp"

namespace mallet {
namespace {

using test::file_error_of;

TEST(MetricsConfig, TheShippedFileEqualsTheDefaultsAndIsOff) {
  const AppConfig shipped = config::load_app_config(test::config_dir() / "mallet.toml");
  const AppConfig defaults;
  EXPECT_EQ(shipped.metrics.textfile, defaults.metrics.textfile);
  EXPECT_EQ(shipped.metrics.interval_s, defaults.metrics.interval_s);
  EXPECT_TRUE(defaults.metrics.textfile.empty());
  EXPECT_EQ(defaults.metrics.interval_s, 15.0);
}

TEST(MetricsConfig, TheFileAndTheIntervalAreRead) {
  const AppConfig c = config::parse_app_config(
      "[metrics]\ntextfile = \"/var/lib/prometheus/node-exporter/mallet.prom\"\ninterval_s = 30\n", "/etc/mallet/mallet.toml");
  EXPECT_EQ(c.metrics.textfile, "/var/lib/prometheus/node-exporter/mallet.prom");
  EXPECT_EQ(c.metrics.interval_s, 30.0);
  // Relative: next to the settings file, as [input] replay_file.
  const AppConfig r = config::parse_app_config("[metrics]\ntextfile = \"m/mallet.prom\"\n", "/etc/mallet/mallet.toml");
  EXPECT_EQ(r.metrics.textfile, "/etc/mallet/m/mallet.prom");
}

TEST(MetricsConfig, AnIntervalOutOfRangeNamesFileLineAndKey) {
  for (const char* bad : {"0", "0.5", "3601", "-15"}) {
    const FileError e = file_error_of([&] {
      config::parse_app_config(std::string("quality = \"balanced\"\n\n[metrics]\ninterval_s = ") + bad + "\n", "k.toml");
    });
    EXPECT_EQ(e.file(), "k.toml");
    EXPECT_EQ(e.line(), 4u) << e.what();
    EXPECT_NE(std::string(e.what()).find("metrics.interval_s"), std::string::npos) << e.what();
  }
}

TEST(MetricsConfig, AFolderAMisspeltKeyAndAWrongTypeAreRefused) {
  const FileError folder =
      file_error_of([] { config::parse_app_config("[metrics]\ntextfile = \"/var/lib/prometheus/\"\n", "k.toml"); });
  EXPECT_EQ(folder.line(), 2u);
  EXPECT_NE(std::string(folder.what()).find("folder"), std::string::npos) << folder.what();
  const FileError typo = file_error_of([] { config::parse_app_config("[metrics]\ninterval = 15\n", "k.toml"); });
  EXPECT_EQ(typo.line(), 2u);
  EXPECT_NE(std::string(typo.what()).find("unknown key"), std::string::npos) << typo.what();
  const FileError type = file_error_of([] { config::parse_app_config("[metrics]\ntextfile = 3\n", "k.toml"); });
  EXPECT_EQ(type.line(), 2u) << type.what();
}

}  // namespace
}  // namespace mallet
