// ParameterStore: registration, validation, staging/atomic apply and JSON round trips.
#include "stride/firmware/parameter_store.hpp"

#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "temp_dir.hpp"

namespace stride::fw {
namespace {

void register_params(ParameterStore& store) {
  store.add_real("walk.step_time", 0.85, 0.3, 1.5, "s", "duration of one step");
  store.add({"loop.rate_hz", ParamType::kInt, 100, 10, 1000, "Hz", "control rate", false, true});
  store.add({"walk.enabled", ParamType::kBool, 1, 0, 1, "", "walk allowed", false, false});
  store.add({"robot.mass", ParamType::kReal, 6.46, 0, 100, "kg", "mass", true, false});
}

TEST(ParameterStore, RegistersAndReadsDefaults) {
  ParameterStore store;
  register_params(store);
  EXPECT_EQ(store.size(), 4u);
  const auto h = store.find("walk.step_time");
  ASSERT_TRUE(h.has_value());
  EXPECT_DOUBLE_EQ(store.value(*h), 0.85);
  EXPECT_FALSE(store.find("walk.nope").has_value());
}

TEST(ParameterStore, RejectsBadRegistration) {
  ParameterStore store;
  register_params(store);
  EXPECT_THROW(store.add_real("walk.step_time", 1, 0, 2, "s", "dup"), std::invalid_argument);
  EXPECT_THROW(store.add_real("a.b", 3, 0, 2, "s", "default outside"), std::invalid_argument);
  EXPECT_THROW(store.add_real("a.c", 1, 2, 0, "s", "min > max"), std::invalid_argument);
}

TEST(ParameterStore, BadWritesNameTheParameterAndRangeAndChangeNothing) {
  ParameterStore store;
  register_params(store);
  const Status out_of_range = store.stage("walk.step_time", 2.0);
  ASSERT_FALSE(out_of_range);
  EXPECT_NE(out_of_range.message().find("walk.step_time"), std::string::npos);
  EXPECT_NE(out_of_range.message().find("[0.3, 1.5]"), std::string::npos);
  EXPECT_FALSE(store.stage("loop.rate_hz", 99.5));
  EXPECT_FALSE(store.stage("walk.enabled", 0.5));
  EXPECT_FALSE(store.stage("robot.mass", 5.0));
  EXPECT_FALSE(store.stage("walk.unknown", 1.0));
  EXPECT_FALSE(store.stage("walk.step_time", std::nan("")));
  EXPECT_FALSE(store.has_staged());
  EXPECT_FALSE(store.apply_staged());
  EXPECT_DOUBLE_EQ(store.value(*store.find("walk.step_time")), 0.85);
}

TEST(ParameterStore, BatchIsAllOrNothing) {
  ParameterStore store;
  register_params(store);
  EXPECT_FALSE(store.stage({{"walk.step_time", 0.9}, {"loop.rate_hz", 5000}}));
  EXPECT_FALSE(store.apply_staged());
  EXPECT_DOUBLE_EQ(store.value(*store.find("walk.step_time")), 0.85);

  ASSERT_TRUE(store.stage({{"walk.step_time", 0.9}, {"loop.rate_hz", 90}}));
  // Nothing changes until the loop applies the batch at the next tick.
  EXPECT_DOUBLE_EQ(store.value(*store.find("walk.step_time")), 0.85);
  EXPECT_TRUE(store.apply_staged());
  EXPECT_DOUBLE_EQ(store.value(*store.find("walk.step_time")), 0.9);
  EXPECT_DOUBLE_EQ(store.value(*store.find("loop.rate_hz")), 90);
  EXPECT_EQ(store.applied_batches(), 1u);
}

TEST(ParameterStore, JsonRoundTripAndNestedObjects) {
  test::TempDir dir;
  ParameterStore store;
  register_params(store);
  ASSERT_TRUE(store.set_now({{"walk.step_time", 1.1}, {"walk.enabled", 0}}));
  const auto path = dir.path() / "params.json";
  ASSERT_TRUE(store.save_file(path));

  ParameterStore other;
  register_params(other);
  ASSERT_TRUE(other.load_file_now(path));
  EXPECT_DOUBLE_EQ(other.value(*other.find("walk.step_time")), 1.1);
  EXPECT_DOUBLE_EQ(other.value(*other.find("walk.enabled")), 0.0);

  std::vector<ParamWrite> batch;
  ASSERT_TRUE(other.parse_json(nlohmann::json::parse(R"({"walk": {"step_time": 0.5}})"), batch));
  ASSERT_EQ(batch.size(), 1u);
  EXPECT_EQ(batch[0].first, "walk.step_time");
}

TEST(ParameterStore, BrokenFileIsRefusedWithFieldNamedAndStoreUnchanged) {
  test::TempDir dir;
  ParameterStore store;
  register_params(store);
  const auto before = store.to_json();

  const auto bad_range = dir.write("range.json", R"({"walk.step_time": 0.9, "loop.rate_hz": 7})");
  Status s = store.load_file_now(bad_range);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("loop.rate_hz"), std::string::npos) << s.message();
  EXPECT_NE(s.message().find("range.json"), std::string::npos) << s.message();

  const auto bad_type = dir.write("type.json", R"({"walk.enabled": 1})");
  s = store.load_file_now(bad_type);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("walk.enabled"), std::string::npos) << s.message();

  const auto bad_json = dir.write("syntax.json", R"({"walk.step_time": )");
  s = store.stage_file(bad_json);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("not valid JSON"), std::string::npos) << s.message();

  EXPECT_FALSE(store.stage_file(dir.path() / "missing.json"));
  EXPECT_EQ(store.to_json(), before);
  EXPECT_FALSE(store.has_staged());
}

TEST(ParameterStore, ListFiltersByPrefix) {
  ParameterStore store;
  register_params(store);
  EXPECT_EQ(store.list("walk.").size(), 2u);
  EXPECT_EQ(store.list().size(), 4u);
  EXPECT_EQ(store.describe_json("loop.").size(), 1u);
}

}  // namespace
}  // namespace stride::fw
