// The walk's defaults live in the firmware's code (each engine registers its parameters with their
// default values); firmware/config/stepping-turf.json repeats them as a file a team can start
// from (issue 44 point 2: one source, and a test tying every copy to it). Every value the file
// sets must be the compiled-in default, bit for bit, so that the file and a firmware without a
// parameter file walk the same.
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "stride/firmware/firmware.hpp"

namespace stride::fw {
namespace {

TEST(ShippedDefaults, SteppingTurfRepeatsTheCompiledInWalkDefaultsExactly) {
  std::unique_ptr<Firmware> firmware;
  ASSERT_TRUE(Firmware::create({}, firmware));
  const std::filesystem::path path = data_dir() / "config" / "stepping-turf.json";
  std::ifstream file(path);
  ASSERT_TRUE(file) << path;
  const nlohmann::json values = nlohmann::json::parse(file);
  ASSERT_GE(values.size(), 10u);
  for (const auto& [name, value] : values.items()) {
    const std::optional<ParamHandle> handle = firmware->params().find(name);
    ASSERT_TRUE(handle.has_value()) << name << ": not a firmware parameter";
    EXPECT_EQ(firmware->params().spec(*handle).default_value, value.get<double>()) << name;
  }
}

}  // namespace
}  // namespace stride::fw
