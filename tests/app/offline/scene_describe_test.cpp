// `mallet scene describe` prints the contract's JSON: check it with a real JSON parser.
#include <fstream>

#include <gtest/gtest.h>

#include "app/offline/scene_describe.hpp"
#include "run_cli.hpp"
#include "test_paths.hpp"

namespace mallet::app {
namespace {

TEST(SceneDescribeCli, PrintsValidJsonWithTheContractKeys) {
  const auto dir = test::scratch_dir();
  const test::CliResult r = test::run_mallet("scene describe --scene " + test::percussion_scene().string() + " > " +
                                             (dir / "scene.json").string());
  ASSERT_EQ(r.status, 0) << r.output;
  // python3 is part of every Debian system; its json module is the independent parser.
  const std::string check =
      "python3 -c \"import json,sys; d=json.load(open(sys.argv[1])); t=d['targets'];"
      "assert isinstance(d['mallet_radius'], float);"
      "assert len(t)==16 and all(set(['id','instrument','material','note','frequency_hz','x_min','x_max','top_y'])<=set(x) for x in t);"
      "assert [x['note'] for x in t]==[72,74,76,77,79,81,83,84,84,86,88,89,91,93,95,96];"
      "assert t[0]['instrument']=='xylophone' and t[15]['material']=='metal';"
      "assert abs(t[5]['frequency_hz']-880.0)<1e-9;"
      "assert all(x['x_min']<x['x_max'] for x in t);"
      "assert set(['left_m','right_m','top_m','bottom_m'])<=set(d['screen_to_world']);"
      "m=d['materials']; assert set(m)=={'wood','metal'} and m['metal']['actuator']['freq_hz']==300;"
      "assert set(m['wood']['visual'])=={'amplitude_s','decay_per_s','freq_hz'}\" " +
      (dir / "scene.json").string();
  EXPECT_EQ(std::system(check.c_str()), 0);
}

// Numbers keep the contract's form: twelve significant digits, whole numbers without a
// point (scripts that compare the text, or read 440 as an integer, keep working).
TEST(SceneDescribe, NumbersHaveTwelveSignificantDigitsAndWholeOnesNoPoint) {
  const std::string json = describe_scene_json(test::percussion());
  for (const char* text : {"\"frequency_hz\": 523.251130601,", "\"tuning_a4_hz\": 440,", "\"note\": 72,",
                           "\"decay_per_s\": 80,", "\"mallet_radius\": 0.015,"})
    EXPECT_NE(json.find(text), std::string::npos) << text << " in\n" << json;
}

TEST(SceneDescribeCli, ABrokenSceneExitsTwoNamingTheLine) {
  const auto dir = test::scratch_dir();
  std::ofstream(dir / "s.toml") << "name = \"x\"\nmallet_radius_m = -1\nmaterials_file = \""
                                << (test::config_dir() / "materials.toml").string() << "\"\n";
  const test::CliResult r = test::run_mallet("scene describe --scene " + (dir / "s.toml").string());
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.output.find("s.toml:2:"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("mallet_radius_m: must be > 0"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace mallet::app
