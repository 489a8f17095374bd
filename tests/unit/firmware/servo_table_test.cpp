// ServoTable: the shipped table loads; broken tables are refused naming file and field.
#include "stride/firmware/servo_table.hpp"

#include <fstream>
#include <sstream>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "temp_dir.hpp"

namespace stride::fw {
namespace {

nlohmann::json shipped() {
  std::ifstream in(ServoTable::default_path());
  return nlohmann::json::parse(in);
}

std::string load_error(const test::TempDir& dir, const nlohmann::json& doc) {
  const auto path = dir.write("servo_table.json", doc.dump());
  ServoTable table;
  const Status s = ServoTable::load(path, table);
  return s ? std::string() : s.message();
}

TEST(ServoTable, ShippedTableLoadsWithTwentyServos) {
  const ServoTable& t = ServoTable::defaults();
  EXPECT_EQ(t[0].id, 1);
  EXPECT_EQ(t[0].name, "r_shoulder_pitch");
  EXPECT_EQ(t[12].name, "r_knee");
  EXPECT_EQ(t[12].model, ServoModel::kMx106);
  EXPECT_EQ(t[18].model, ServoModel::kMx64);
  EXPECT_EQ(t.index_of("l_ankle_roll"), std::optional<std::size_t>(17));
  EXPECT_FALSE(t.index_of("tail").has_value());
  int mx106 = 0;
  for (const auto& s : t.servos()) mx106 += s.model == ServoModel::kMx106 ? 1 : 0;
  EXPECT_EQ(mx106, 12);  // 6 per leg (igus BOM)
}

TEST(ServoTable, BadDirectionIsNamed) {
  test::TempDir dir;
  auto doc = shipped();
  doc["servos"][3]["direction"] = 0;
  const std::string e = load_error(dir, doc);
  EXPECT_NE(e.find("servo_table.json: servos[3].direction"), std::string::npos) << e;
}

TEST(ServoTable, EveryKindOfBrokenEntryIsRefused) {
  test::TempDir dir;
  struct Case {
    const char* field;
    nlohmann::json value;
    const char* expect;
  };
  const Case cases[] = {
      {"id", 21, "servos[5].id"},
      {"id", 1, "duplicate id"},
      {"name", "r_shoulder_pitch", "duplicate name"},
      {"model", "AX-12", "servos[5].model"},
      {"offset_rad", 4.0, "servos[5].offset_rad"},
      {"min_rad", 10.0, "servos[5].min_rad"},
      {"max_rad", "big", "servos[5].max_rad"},
  };
  for (const Case& c : cases) {
    auto doc = shipped();
    doc["servos"][5][c.field] = c.value;
    const std::string e = load_error(dir, doc);
    EXPECT_NE(e.find(c.expect), std::string::npos) << c.field << ": " << e;
  }
  auto missing = shipped();
  missing["servos"][2].erase("direction");
  EXPECT_NE(load_error(dir, missing).find("servos[2].direction: missing"), std::string::npos);
  auto short_list = shipped();
  short_list["servos"].erase(19);
  EXPECT_NE(load_error(dir, short_list).find("expected 20 entries"), std::string::npos);
}

TEST(ServoTable, UnreadableOrInvalidJsonIsRefused) {
  test::TempDir dir;
  ServoTable table;
  EXPECT_FALSE(ServoTable::load(dir.path() / "none.json", table));
  const Status s = ServoTable::load(dir.write("bad.json", "{\"servos\": ["), table);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("not valid JSON"), std::string::npos);
}

}  // namespace
}  // namespace stride::fw
