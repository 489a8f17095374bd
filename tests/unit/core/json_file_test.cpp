// read_json_file (stride/core/json_file.hpp): a file that parses is read; a missing file and a
// file that is not JSON each give one line naming the file, and say which of the two it was.
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "stride/core/json_file.hpp"
#include "temp_dir.hpp"

namespace stride::core {
namespace {

TEST(ReadJsonFile, ReadsAFileThatParses) {
  const test::TempDir tmp;
  const auto path = tmp.write("ok.json", "{\"walk.step_time\": 0.4}\n");
  nlohmann::json doc;
  JsonFileError why = JsonFileError::kNotJson;
  ASSERT_TRUE(read_json_file(path, doc, &why));
  EXPECT_EQ(why, JsonFileError::kNone);
  EXPECT_EQ(doc.at("walk.step_time"), 0.4);
}

TEST(ReadJsonFile, AMissingFileIsNamedAndLeavesTheOutputAlone) {
  const test::TempDir tmp;
  nlohmann::json doc = {{"kept", true}};
  JsonFileError why = JsonFileError::kNone;
  const Status s = read_json_file(tmp.path() / "none.json", doc, &why);
  ASSERT_FALSE(s);
  EXPECT_EQ(s.message(), (tmp.path() / "none.json").string() + ": cannot open for reading");
  EXPECT_EQ(why, JsonFileError::kCannotOpen);
  EXPECT_EQ(doc, (nlohmann::json{{"kept", true}}));
}

TEST(ReadJsonFile, AFileThatIsNotJsonGivesTheParsersReasonOnOneLine) {
  const test::TempDir tmp;
  for (const std::string text : {"{\"a\": ", "{} trailing", ""}) {
    const auto path = tmp.write("bad.json", text);
    nlohmann::json doc;
    JsonFileError why = JsonFileError::kNone;
    const Status s = read_json_file(path, doc, &why);
    ASSERT_FALSE(s) << text;
    EXPECT_EQ(s.message().rfind(path.string() + ": not valid JSON (", 0), 0u) << s.message();
    EXPECT_EQ(s.message().find('\n'), std::string::npos) << s.message();
    EXPECT_EQ(why, JsonFileError::kNotJson);
  }
}

}  // namespace
}  // namespace stride::core
