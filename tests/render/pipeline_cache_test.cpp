// The pipeline cache on disk (src/render/pipeline_cache.cpp), saved by two programs at once
// (tests in parallel, a render beside the kiosk): each save goes through a temporary file of
// its own, so the folder ends with one whole file, no temporary, nothing said, and the next
// start loads it.
#include <filesystem>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "render/pipeline_cache.hpp"
#include "test_paths.hpp"

namespace mallet::render {
namespace {

TEST(PipelineCacheFile, TwoCachesSavingTheSameFileAtOnceLeaveOneWholeFileTheNextStartLoads) {
  const std::filesystem::path dir = test::scratch_dir();
  ContextOptions o;
  o.validation = Validation::required;
  o.device_name = "llvmpipe";
  Context ctx(o);
  ::testing::internal::CaptureStderr();
  {
    const PipelineCache a(ctx, dir);
    const PipelineCache b(ctx, dir);
    EXPECT_FALSE(a.loaded_from_disk());
    ASSERT_EQ(a.file(), b.file());
    const auto save_often = [](const PipelineCache& cache) {
      for (int i = 0; i < 50; ++i) cache.save();
    };
    std::thread first(save_often, std::cref(a));
    std::thread second(save_often, std::cref(b));
    first.join();
    second.join();
  }  // and once more each, as they close
  const std::string said = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(said.find("pipeline cache"), std::string::npos) << said;
  std::vector<std::string> files;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) files.push_back(entry.path().filename().string());
  ASSERT_EQ(files.size(), 1u) << "a temporary file is left beside the cache";
  const PipelineCache again(ctx, dir);
  EXPECT_EQ(again.file().filename().string(), files[0]);
  EXPECT_TRUE(again.loaded_from_disk());
  EXPECT_EQ(ctx.validation_messages(), 0u) << ctx.first_validation_message();
}

}  // namespace
}  // namespace mallet::render
