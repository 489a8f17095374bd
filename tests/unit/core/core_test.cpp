// stride_core: the command-line parser, atomic file replacement, the data directory and XML
// escaping.
#include <cstdlib>
#include <fstream>

#include <gtest/gtest.h>

#include "stride/core/atomic_file.hpp"
#include "stride/core/cli_args.hpp"
#include "stride/core/data_dir.hpp"
#include "stride/core/text_escape.hpp"
#include "temp_dir.hpp"

namespace stride::core {
namespace {

TEST(CliArgs, ParsesOptionsFlagsAndPositionals) {
  CliArgs args;
  args.option("port", "device").option("json", "json", false).option("rate", "hz", true, "100");
  const char* argv[] = {"x", "scan", "--port", "/dev/ttyUSB0", "--json", "--rate=90", "extra"};
  ASSERT_TRUE(args.parse(7, argv));
  EXPECT_EQ(args.get("port"), "/dev/ttyUSB0");
  EXPECT_TRUE(args.has("json"));
  std::int64_t rate = 0;
  ASSERT_TRUE(args.get_int("rate", rate));
  EXPECT_EQ(rate, 90);
  EXPECT_EQ(args.positional(), (std::vector<std::string>{"scan", "extra"}));
}

TEST(CliArgs, ARepeatedOptionKeepsEveryValueInOrder) {
  CliArgs args;
  args.option("push", "repeatable").option("seed", "one value", true, "1");
  const char* argv[] = {"x", "--push", "1,left,1", "--push=2,right,0.5", "--seed", "3"};
  ASSERT_TRUE(args.parse(6, argv));
  EXPECT_EQ(args.get_all("push"), (std::vector<std::string>{"1,left,1", "2,right,0.5"}));
  EXPECT_EQ(args.get("push"), "2,right,0.5");  // get() is the last
  EXPECT_TRUE(args.get_all("seed") == std::vector<std::string>{"3"});
  CliArgs defaults;
  defaults.option("seed", "one value", true, "1");
  const char* none[] = {"x"};
  ASSERT_TRUE(defaults.parse(1, none));
  EXPECT_TRUE(defaults.get_all("seed").empty());  // a default is not a value given
}

TEST(CliArgs, BadInputIsNamed) {
  CliArgs args;
  args.option("port", "device").option("json", "json", false).option("vx", "speed");
  const char* unknown[] = {"x", "--prot", "a"};
  Status s = args.parse(3, unknown);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("--prot"), std::string::npos);
  CliArgs a2 = args;
  const char* missing[] = {"x", "--port"};
  EXPECT_FALSE(a2.parse(2, missing));
  CliArgs a3 = args;
  const char* flag_value[] = {"x", "--json=1"};
  EXPECT_FALSE(a3.parse(2, flag_value));
  CliArgs a4 = args;
  const char* bad_number[] = {"x", "--vx", "fast"};
  ASSERT_TRUE(a4.parse(3, bad_number));
  double vx = 0;
  s = a4.get_double("vx", vx);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("--vx"), std::string::npos);
}

TEST(AtomicFile, ReplacesContentsAndLeavesNoTemporaries) {
  test::TempDir dir;
  const auto path = dir.path() / "out.json";
  ASSERT_TRUE(write_file_atomically(path, "first"));
  ASSERT_TRUE(write_file_atomically(path, "second"));
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(text, "second");
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir.path())) ++files;
  EXPECT_EQ(files, 1);
}

TEST(AtomicFile, FailureNamesTheFileAndKeepsTheOldContents) {
  test::TempDir dir;
  const auto path = dir.path() / "keep.txt";
  ASSERT_TRUE(write_file_atomically(path, "old"));
  const Status s = write_file_atomically(dir.path() / "missing-dir" / "x.txt", "new");
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("missing-dir"), std::string::npos);
  std::ifstream in(path);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_EQ(text, "old");
}

TEST(DataDir, TheEnvironmentThenTheSourceTree) {
  // The test binary is not installed (no share/stride beside it).
  ::unsetenv("STRIDE_DATA_DIR");
  EXPECT_EQ(data_dir("config/servo_table.json", "/src/firmware"), "/src/firmware");
  ::setenv("STRIDE_DATA_DIR", "/opt/robot/share/stride", 1);
  EXPECT_EQ(data_dir("config/servo_table.json", "/src/firmware"), "/opt/robot/share/stride");
  ::setenv("STRIDE_DATA_DIR", "", 1);  // empty: unset
  EXPECT_EQ(data_dir("config/servo_table.json", "/src/firmware"), "/src/firmware");
  ::unsetenv("STRIDE_DATA_DIR");
}

TEST(XmlEscape, TheFiveEntitiesAndNothingElse) {
  EXPECT_EQ(xml_escape("a<b>&\"c\" 'd' \u00b0"), "a&lt;b&gt;&amp;&quot;c&quot; &#39;d&#39; \u00b0");
  EXPECT_EQ(xml_escape(""), "");
}

}  // namespace
}  // namespace stride::core
