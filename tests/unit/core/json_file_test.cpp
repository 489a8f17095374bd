// stride/core/json_file.hpp: a file that parses is read; a missing file and a file that is not
// JSON each give one line naming the file, and say which of the two it was; a JSON Lines log cut
// by a kill keeps its whole lines and counts the damaged ones.
#include <string>
#include <vector>

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

TEST(ReadTextFile, KeepsTheBytesAndTheirJsonParsesWhereNamed) {
  const test::TempDir tmp;
  const std::string text = "{\"a\": 1}\r\n";
  const auto path = tmp.write("robot.json", text);
  std::string read;
  ASSERT_TRUE(read_text_file(path, read));
  EXPECT_EQ(read, text);  // the exact bytes, for a content hash
  nlohmann::json doc;
  ASSERT_TRUE(parse_json_text(read, "robot.json", doc));
  EXPECT_EQ(doc.at("a"), 1);
  const Status bad = parse_json_text("[1,", "robot.json", doc);
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.message().rfind("robot.json: not valid JSON (", 0), 0u) << bad.message();
  EXPECT_EQ(doc.at("a"), 1);  // unchanged on an error
  std::string kept = "kept";
  ASSERT_FALSE(read_text_file(tmp.path() / "none.json", kept));
  EXPECT_EQ(kept, "kept");
}

TEST(ReadJsonLines, SkipsAndCountsDamagedLinesAndKeepsTheWholeOnes) {
  const test::TempDir tmp;
  const auto path = tmp.write("log.jsonl", "{\"n\": 1}\n\n[2]\n{\"n\": 3}\n{\"n\": 4, \"cut");
  std::vector<nlohmann::json> lines;
  JsonLinesDamage damage;
  ASSERT_TRUE(read_json_lines(path, lines, &damage));
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[0].at("n"), 1);
  EXPECT_EQ(lines[1].at("n"), 3);
  EXPECT_EQ(damage.lines, 5u);
  EXPECT_EQ(damage.damaged, 2u);  // an array is not a record, and the cut last line
  EXPECT_EQ(damage.first_line, 3u);
  const Status missing = read_json_lines(tmp.path() / "none.jsonl", lines);
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.message(), (tmp.path() / "none.jsonl").string() + ": cannot open for reading");
  EXPECT_EQ(lines.size(), 2u);
}

}  // namespace
}  // namespace stride::core
