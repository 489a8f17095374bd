// Script JSON loader: the stock scripts, and errors that name the file, the frame and the field.
#include <algorithm>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "stride/firmware/script/script.hpp"
#include "temp_dir.hpp"

namespace stride::fw {
namespace {

const ServoTable& servos() {
  return ServoTable::defaults();
}

std::string one_target_script(const std::string& target_body, const std::string& frame_extra = "",
                              int duration = 500) {
  return R"({"name": "probe", "frames": [
    {"duration_ms": 400, "targets": [{"servo": "r_knee", "position": 0.3, "gain": 20, "torque": 100}]},
    {"duration_ms": )" +
         std::to_string(duration) + frame_extra + R"(, "targets": [
      {"servo": "l_knee", "position": 0.3, "gain": 20, "torque": 100},
      )" +
         target_body + R"(]}]})";
}

Status load_text(const test::TempDir& dir, const std::string& text, Script& out) {
  return load_script_file(dir.write("probe.json", text), servos(), out);
}

void expect_error(const std::string& text, const std::string& part1, const std::string& part2) {
  test::TempDir dir;
  Script script;
  const Status status = load_text(dir, text, script);
  ASSERT_FALSE(status) << "accepted: " << text;
  EXPECT_NE(status.message().find("probe.json"), std::string::npos) << status.message();
  EXPECT_NE(status.message().find(part1), std::string::npos) << status.message();
  EXPECT_NE(status.message().find(part2), std::string::npos) << status.message();
  EXPECT_EQ(status.message().find('\n'), std::string::npos) << "one line: " << status.message();
}

TEST(ScriptLoader, AcceptsAWellFormedScript) {
  test::TempDir dir;
  Script script;
  const Status status = load_text(
      dir,
      one_target_script(R"({"servo": "head_yaw", "position": -0.5, "gain": 100, "torque": 0})"),
      script);
  ASSERT_TRUE(status) << status.message();
  EXPECT_EQ(script.name, "probe");
  ASSERT_EQ(script.frames.size(), 2u);
  EXPECT_EQ(script.frames[1].duration_ms, 500);
  ASSERT_EQ(script.frames[1].targets.size(), 2u);
  EXPECT_EQ(script.frames[1].targets[1].servo, *servos().index_of("head_yaw"));
  EXPECT_DOUBLE_EQ(script.frames[1].targets[1].position_rad, -0.5);
  EXPECT_DOUBLE_EQ(script.frames[1].targets[1].gain, 100);
  EXPECT_DOUBLE_EQ(script.frames[1].targets[1].torque, 0);
  EXPECT_EQ(script.total_duration_ms(), 900);
}

TEST(ScriptLoader, ErrorsNameFrameAndField) {
  expect_error(one_target_script(R"({"servo": "r_kne", "position": 0.1, "gain": 20, "torque": 1})"),
               "frames[1].targets[1].servo", "r_kne");
  expect_error(
      one_target_script(R"({"servo": "r_knee", "position": 3.5, "gain": 20, "torque": 1})"),
      "frames[1].targets[1].position", "r_knee limits");
  expect_error(
      one_target_script(R"({"servo": "r_knee", "position": "x", "gain": 20, "torque": 1})"),
      "frames[1].targets[1].position", "must be a number");
  expect_error(one_target_script(R"({"servo": "r_knee", "position": 0.1, "torque": 1})"),
               "frames[1].targets[1].gain", "missing");
  expect_error(
      one_target_script(R"({"servo": "r_knee", "position": 0.1, "gain": 101, "torque": 1})"),
      "frames[1].targets[1].gain", "outside [0, 100]");
  expect_error(
      one_target_script(R"({"servo": "r_knee", "position": 0.1, "gain": 20, "torque": -1})"),
      "frames[1].targets[1].torque", "outside [0, 100]");
  expect_error(one_target_script(R"({"servo": "r_knee", "postion": 0.1, "gain": 20, "torque": 1})"),
               "frames[1].targets[1].postion", "unknown field");
  expect_error(
      one_target_script(R"({"servo": "l_knee", "position": 0.1, "gain": 20, "torque": 1})"),
      "frames[1].targets[1].servo", "listed twice");
  expect_error(
      one_target_script(R"({"servo": "r_knee", "position": 0.1, "gain": 20, "torque": 1})", "", 0),
      "frames[1].duration_ms", "integer 1..60000");
  expect_error(one_target_script(R"({"servo": "r_knee", "position": 0.1, "gain": 20, "torque": 1})",
                                 ".5", 10),
               "frames[1].duration_ms", "10.5");
  expect_error(one_target_script(R"({"servo": "r_knee", "position": 0.1, "gain": 20, "torque": 1})",
                                 R"(, "speed": 3)"),
               "frames[1].speed", "unknown field");
  expect_error(one_target_script("[]"), "frames[1].targets[1]", "must be an object");
}

TEST(ScriptLoader, ErrorsForTheDocument) {
  expect_error("{\"name\": \"probe\", \"frames\": [", "probe.json", "not valid JSON");
  expect_error(R"({"name": "probe", "frames": []})", "frames", "non-empty array");
  expect_error(R"({"name": "Bad Name", "frames": []})", "name", "[a-z0-9_]+");
  expect_error(R"({"frames": []})", "name", "missing");
  expect_error(R"({"name": "probe", "frames": [{"duration_ms": 10, "targets": []}]})",
               "frames[0].targets", "non-empty array");
  std::string many = R"({"name": "probe", "frames": [)";
  for (int i = 0; i < 65; ++i) {
    many +=
        std::string(i ? "," : "") +
        R"({"duration_ms": 10, "targets": [{"servo": "r_knee", "position": 0.1, "gain": 20, "torque": 1}]})";
  }
  expect_error(many + "]}", "frames", "at most 64");
}

TEST(ScriptLoader, MissingFileIsAnError) {
  Script script;
  const Status status = load_script_file("/nonexistent/kick.json", servos(), script);
  ASSERT_FALSE(status);
  EXPECT_NE(status.message().find("/nonexistent/kick.json"), std::string::npos);
}

TEST(ScriptLoader, FolderRejectsTwoScriptsWithOneName) {
  test::TempDir dir;
  const std::string body =
      R"({"name": "same", "frames": [{"duration_ms": 10, "targets": [{"servo": "r_knee", "position": 0.1, "gain": 20, "torque": 1}]}]})";
  dir.write("a.json", body);
  dir.write("b.json", body);
  std::vector<Script> scripts;
  const Status status = load_script_folder(dir.path(), servos(), scripts);
  ASSERT_FALSE(status);
  EXPECT_NE(status.message().find("b.json"), std::string::npos) << status.message();
  EXPECT_NE(status.message().find("'same'"), std::string::npos) << status.message();
  EXPECT_TRUE(scripts.empty());
}

TEST(ScriptLoader, JsonRoundTrip) {
  std::vector<Script> scripts;
  ASSERT_TRUE(load_script_folder(default_script_folder(), servos(), scripts));
  for (const Script& script : scripts) {
    Script again;
    ASSERT_TRUE(parse_script(script_to_json(script, servos()), "roundtrip", servos(), again));
    EXPECT_EQ(script_to_json(again, servos()), script_to_json(script, servos())) << script.name;
  }
}

TEST(StockScripts, KickRightIsTheIgusKickInUrdfAngles) {
  Script kick;
  const Status status =
      load_script_file(default_script_folder() / "kick_right.json", servos(), kick);
  ASSERT_TRUE(status) << status.message();
  ASSERT_EQ(kick.frames.size(), 6u);
  EXPECT_EQ(kick.total_duration_ms(), 3100);
  const int durations[] = {1000, 600, 300, 200, 500, 500};
  for (std::size_t f = 0; f < 6; ++f) {
    EXPECT_EQ(kick.frames[f].duration_ms, durations[f]);
    EXPECT_EQ(kick.frames[f].targets.size(), 18u) << "no head servos";
  }
  // NUbots shoulder pitch 1.9635 is URDF 1.9635 - pi/2 (igus.md 1.5).
  const auto r_sp = *servos().index_of("r_shoulder_pitch");
  EXPECT_NEAR(kick.frames[0].targets[r_sp].position_rad, 0.3927, 1e-4);
  // Frame 4 (200 ms): R_HIP_PITCH -0.8608; frame 2 R_ANKLE_ROLL 0.6276; frame 6 R_KNEE gain 30.
  EXPECT_DOUBLE_EQ(kick.frames[3].targets[*servos().index_of("r_hip_pitch")].position_rad, -0.8608);
  EXPECT_DOUBLE_EQ(kick.frames[1].targets[*servos().index_of("r_ankle_roll")].position_rad, 0.6276);
  EXPECT_DOUBLE_EQ(kick.frames[5].targets[*servos().index_of("r_knee")].gain, 30);
  // Stride's one change (README): the support leg's pitch joints at gain 50 instead of 20.
  for (const ScriptFrame& frame : kick.frames) {
    for (const char* name : {"l_hip_pitch", "l_knee", "l_ankle_pitch"}) {
      EXPECT_DOUBLE_EQ(frame.targets[*servos().index_of(name)].gain, 50) << name;
    }
    EXPECT_DOUBLE_EQ(frame.targets[*servos().index_of("l_hip_roll")].gain,
                     &frame == &kick.frames.back() ? 30 : 20);
  }
}

TEST(StockScripts, KickLeftMirrorsKickRight) {
  Script right, left;
  ASSERT_TRUE(load_script_file(default_script_folder() / "kick_right.json", servos(), right));
  ASSERT_TRUE(load_script_file(default_script_folder() / "kick_left.json", servos(), left));
  ASSERT_EQ(left.frames.size(), right.frames.size());
  for (std::size_t f = 0; f < right.frames.size(); ++f) {
    EXPECT_EQ(left.frames[f].duration_ms, right.frames[f].duration_ms);
    ASSERT_EQ(left.frames[f].targets.size(), right.frames[f].targets.size());
    for (const ScriptTarget& r : right.frames[f].targets) {
      const std::string& name = servos()[r.servo].name;
      const std::string mirrored = (name[0] == 'r' ? "l" : "r") + name.substr(1);
      const auto mirrored_index = *servos().index_of(mirrored);
      const ScriptTarget* l = nullptr;
      for (const ScriptTarget& t : left.frames[f].targets) {
        if (t.servo == mirrored_index) l = &t;
      }
      ASSERT_NE(l, nullptr) << mirrored;
      const bool flips =
          name.find("roll") != std::string::npos || name.find("yaw") != std::string::npos;
      EXPECT_DOUBLE_EQ(l->position_rad, flips ? -r.position_rad : r.position_rad)
          << "frame " << f + 1 << " " << mirrored;
      EXPECT_DOUBLE_EQ(l->gain, r.gain);
      EXPECT_DOUBLE_EQ(l->torque, r.torque);
    }
  }
}

TEST(StockScripts, AllLoadAndStandIsTheIgusStand) {
  std::vector<Script> scripts;
  const Status status = load_script_folder(default_script_folder(), servos(), scripts);
  ASSERT_TRUE(status) << status.message();
  std::vector<std::string> names;
  for (const Script& s : scripts) names.push_back(s.name);
  for (const char* expected : {"stand", "kick_right", "kick_left", "get_up_front", "get_up_back"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  }
  const auto stand = std::find_if(scripts.begin(), scripts.end(),
                                  [](const Script& s) { return s.name == "stand"; });
  ASSERT_NE(stand, scripts.end());
  ASSERT_EQ(stand->frames.size(), 1u);
  EXPECT_EQ(stand->frames[0].duration_ms, 3000);
  for (const ScriptTarget& t : stand->frames[0].targets) EXPECT_DOUBLE_EQ(t.gain, 30);
  EXPECT_DOUBLE_EQ(stand->frames[0].targets[*servos().index_of("l_knee")].position_rad, 0.2945);
  EXPECT_NEAR(stand->frames[0].targets[*servos().index_of("l_shoulder_pitch")].position_rad, 0.3927,
              1e-4);
}

}  // namespace
}  // namespace stride::fw
