// Console command interpreter: every command and every error path against a real Firmware
// whose controller is stepped by a background "loop" thread (1 ms per tick), so staged
// changes really land at a tick boundary.
#include "stride/firmware/console/command_interpreter.hpp"

#include <atomic>
#include <fstream>
#include <memory>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "firmware_fixture.hpp"
#include "temp_dir.hpp"

namespace stride::fw::console {
namespace {

class ConsoleInterpreter : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(Firmware::create({}, firmware_));
    ParamSpec build{"test.build", ParamType::kInt, 7, 0, 100, "", "build number", true, false};
    firmware_->params().add(build);
    ConsoleContext context;
    context.params = &firmware_->params();
    context.controller = &firmware_->controller();
    context.servos = &firmware_->servos();
    context.default_file = dir_.path() / "default.json";
    context.loop_status = [] { return std::vector<std::string>{"loop: fake line"}; };
    context.apply_timeout = std::chrono::milliseconds(2000);
    interpreter_ = std::make_unique<CommandInterpreter>(context);
    ticker_ = std::thread([this] {
      hal::Tick tick = 0;
      const auto upright = hal::ScriptedRobot::standing_frame();
      const auto lying = test::tilted_frame(1.5);
      while (!stop_.load()) {
        firmware_->params().apply_staged();
        (void)firmware_->controller().step(fallen_.load() ? lying : upright, tick++);
        std::this_thread::sleep_for(std::chrono::milliseconds(1));
      }
    });
    wait_ticks(3);
  }
  void TearDown() override {
    stop_ = true;
    if (ticker_.joinable()) ticker_.join();
  }

  void wait_ticks(int n) {
    const hal::Tick start = firmware_->controller().status().tick;
    while (firmware_->controller().status().tick < start + n) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  }
  Reply run(std::string_view line) { return interpreter_->execute(line); }
  double live(const std::string& name) {
    double v = 0;
    EXPECT_TRUE(firmware_->params().get(name, v));
    return v;
  }
  static void expect_err(const Reply& r, std::string_view code) {
    EXPECT_EQ(r.final_line.rfind("err " + std::string(code) + " ", 0), 0u) << r.final_line;
    EXPECT_FALSE(r.ok());
  }

  test::TempDir dir_;
  std::unique_ptr<Firmware> firmware_;
  std::unique_ptr<CommandInterpreter> interpreter_;
  std::thread ticker_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> fallen_{false};
};

TEST_F(ConsoleInterpreter, HelpListsEveryCommand) {
  const Reply r = run("help");
  EXPECT_EQ(r.final_line, "ok 13 commands");
  ASSERT_EQ(r.data.size(), 13u);
  for (const char* c : {"help", "list", "get", "set", "reset", "save", "load", "flash", "status",
                        "torque", "walk", "stop", "script"}) {
    bool found = false;
    for (const auto& line : r.data) found = found || line.rfind(c, 0) == 0;
    EXPECT_TRUE(found) << c;
  }
}

TEST_F(ConsoleInterpreter, EmptyAndUnknownCommands) {
  EXPECT_EQ(run("").final_line, "ok");
  EXPECT_EQ(run("   ").final_line, "ok");
  expect_err(run("fly away"), "unknown-command");
  expect_err(run(std::string(300, 'z')), "unknown-command");
  EXPECT_LT(run(std::string(300, 'z')).final_line.size(), 120u);  // the echo is shortened
}

TEST_F(ConsoleInterpreter, ListAllAndByPrefix) {
  const Reply all = run("list");
  EXPECT_EQ(all.final_line, "ok " + std::to_string(firmware_->params().size()) + " parameters");
  EXPECT_EQ(all.data.size(), firmware_->params().size());
  const Reply stand = run("list stand.");
  ASSERT_EQ(stand.data.size(), 2u);
  EXPECT_EQ(stand.data[1].rfind("stand.gain = 30  real [5, 100] default 30  # ", 0), 0u)
      << stand.data[1];
  const Reply flags = run("list loop");
  ASSERT_EQ(flags.data.size(), 1u);
  EXPECT_NE(flags.data[0].find("needs-restart"), std::string::npos);
  EXPECT_NE(run("list test.").data[0].find("read-only"), std::string::npos);
  EXPECT_EQ(run("list nothing.here").final_line, "ok 0 parameters");
  expect_err(run("list a b"), "usage");
}

TEST_F(ConsoleInterpreter, Get) {
  EXPECT_EQ(run("get stand.gain").final_line, "ok stand.gain = 30");
  EXPECT_EQ(run("get loop.rate_hz").final_line, "ok loop.rate_hz = 100");
  EXPECT_EQ(run("get motion.get_up").final_line, "ok motion.get_up = true");
  expect_err(run("get no.such"), "unknown-parameter");
  expect_err(run("get"), "usage");
  expect_err(run("get a b"), "usage");
}

TEST_F(ConsoleInterpreter, SetAppliesAtATickAndValidates) {
  const auto batches = firmware_->params().applied_batches();
  EXPECT_EQ(run("set stand.gain 42.5").final_line, "ok stand.gain = 42.5");
  EXPECT_EQ(live("stand.gain"), 42.5);  // the loop took it before the reply
  EXPECT_EQ(firmware_->params().applied_batches(), batches + 1);
  EXPECT_EQ(run("get stand.gain").final_line, "ok stand.gain = 42.5");

  expect_err(run("set no.such 1"), "unknown-parameter");
  expect_err(run("set test.build 8"), "read-only");
  expect_err(run("set stand.gain fast"), "bad-value");
  expect_err(run("set stand.gain 1e3"), "bad-value");
  expect_err(run("set stand.gain nan"), "bad-value");
  expect_err(run("set stand.gain 4.9"), "bad-value");
  const Reply range = run("set stand.gain 101");
  EXPECT_EQ(range.final_line, "err bad-value stand.gain: 101 outside the allowed range [5, 100]");
  expect_err(run("set safety.fall_ticks 2.5"), "bad-value");
  expect_err(run("set motion.get_up maybe"), "bad-value");
  expect_err(run("set stand.gain"), "usage");
  expect_err(run("set stand.gain 1 2"), "usage");
  EXPECT_EQ(live("stand.gain"), 42.5);  // nothing changed by the failures

  EXPECT_EQ(run("set motion.get_up off").final_line, "ok motion.get_up = false");
  EXPECT_EQ(live("motion.get_up"), 0.0);
  EXPECT_EQ(run("set safety.fall_ticks +12").final_line, "ok safety.fall_ticks = 12");
}

TEST_F(ConsoleInterpreter, NeedsRestartIsAcceptedWithANote) {
  const Reply r = run("set loop.rate_hz 50");
  EXPECT_TRUE(r.ok());
  EXPECT_NE(r.final_line.find("takes effect after a restart"), std::string::npos) << r.final_line;
  EXPECT_EQ(live("loop.rate_hz"), 50.0);  // stored (save keeps it), period unchanged
  EXPECT_EQ(firmware_->controller().period_ns(), 10'000'000);
  // Setting it to the value it has needs no note.
  EXPECT_EQ(run("set loop.rate_hz 50").final_line, "ok loop.rate_hz = 50");
}

TEST_F(ConsoleInterpreter, Reset) {
  ASSERT_TRUE(run("set stand.gain 60").ok());
  ASSERT_TRUE(run("set stand.ramp_time 3").ok());
  EXPECT_EQ(run("reset stand.gain").final_line, "ok stand.gain = 30");
  EXPECT_EQ(live("stand.gain"), 30.0);
  EXPECT_EQ(live("stand.ramp_time"), 3.0);
  const Reply all = run("reset all");
  EXPECT_TRUE(all.ok()) << all.final_line;
  EXPECT_EQ(live("stand.ramp_time"), 1.5);
  expect_err(run("reset no.such"), "unknown-parameter");
  expect_err(run("reset test.build"), "read-only");
  expect_err(run("reset"), "usage");
}

TEST_F(ConsoleInterpreter, SaveWritesEveryValueAtomically) {
  ASSERT_TRUE(run("set stand.gain 55").ok());
  const auto file = dir_.path() / "saved.json";
  const Reply r = run("save " + file.string());
  EXPECT_EQ(r.final_line, "ok saved " + std::to_string(firmware_->params().size()) +
                              " parameters to " + file.string());
  nlohmann::json doc;
  std::ifstream(file) >> doc;
  EXPECT_EQ(doc["stand.gain"], 55.0);
  EXPECT_EQ(doc.size(), firmware_->params().size());
  for (const auto& entry : std::filesystem::directory_iterator(dir_.path())) {
    EXPECT_EQ(entry.path().filename(), "saved.json");  // no temporary left behind
  }
  // Default file.
  EXPECT_TRUE(run("save").ok());
  EXPECT_TRUE(std::filesystem::exists(dir_.path() / "default.json"));
  expect_err(run("save " + (dir_.path() / "missing" / "x.json").string()), "io");
  expect_err(run("save a b"), "usage");
}

TEST_F(ConsoleInterpreter, LoadValidatesTheWholeFileFirst) {
  const auto good = dir_.write("good.json", R"({"stand": {"gain": 44, "ramp_time": 2}})");
  EXPECT_EQ(run("load " + good.string()).final_line,
            "ok loaded 2 parameters from " + good.string());
  EXPECT_EQ(live("stand.gain"), 44.0);
  EXPECT_EQ(live("stand.ramp_time"), 2.0);

  // One bad value: nothing of the file is applied.
  const auto bad = dir_.write("bad.json", R"({"stand.ramp_time": 5, "stand.gain": 500})");
  const Reply r = run("load " + bad.string());
  expect_err(r, "bad-file");
  EXPECT_NE(r.final_line.find("stand.gain"), std::string::npos);
  EXPECT_NE(r.final_line.find("nothing applied"), std::string::npos);
  EXPECT_EQ(live("stand.ramp_time"), 2.0);
  expect_err(run("load " + dir_.write("u.json", R"({"stand.speed": 1})").string()), "bad-file");
  expect_err(run("load " + dir_.write("t.json", R"({"stand.gain": "high"})").string()), "bad-file");
  expect_err(run("load " + dir_.write("j.json", "{\"stand.gain\": 4").string()), "bad-file");
  expect_err(run("load " + (dir_.path() / "absent.json").string()), "io");
  expect_err(run("load a b"), "usage");
  // Default file: what save wrote.
  ASSERT_TRUE(run("save").ok());
  ASSERT_TRUE(run("set stand.gain 70").ok());
  EXPECT_TRUE(run("load").ok());
  EXPECT_EQ(live("stand.gain"), 44.0);
}

TEST_F(ConsoleInterpreter, FlashIsAllOrNothing) {
  EXPECT_EQ(run(R"(flash {"stand":{"gain":33,"ramp_time":1.25},"motion.get_up":false})").final_line,
            "ok flashed 3 parameters");
  EXPECT_EQ(live("stand.gain"), 33.0);
  EXPECT_EQ(live("stand.ramp_time"), 1.25);
  EXPECT_EQ(live("motion.get_up"), 0.0);
  const Reply bad = run(R"(flash {"stand.gain": 35, "motion.get_up": 3})");
  expect_err(bad, "bad-file");
  EXPECT_EQ(live("stand.gain"), 33.0);
  expect_err(run(R"(flash {"stand.gain": 35)"), "bad-file");
  expect_err(run("flash [1, 2]"), "bad-file");
  expect_err(run(R"(flash {"test.build": 9})"), "bad-file");  // read-only, changed
  EXPECT_TRUE(run(R"(flash {"test.build": 7})").ok());        // read-only, unchanged
  expect_err(run("flash"), "usage");
  expect_err(run("flash   "), "usage");
}

TEST_F(ConsoleInterpreter, StatusReportsMotionLoopSafetyAndServos) {
  const Reply r = run("status");
  EXPECT_EQ(r.final_line, "ok status");
  ASSERT_GE(r.data.size(), 26u);
  EXPECT_EQ(r.data[0].rfind("motion: stand  walk requested: no  torque: on  tick: ", 0), 0u)
      << r.data[0];
  int servo_lines = 0;
  bool loop_line = false, safety_line = false, cm730_line = false;
  for (const auto& line : r.data) {
    servo_lines += line.rfind("servo ", 0) == 0 ? 1 : 0;
    loop_line = loop_line || line == "loop: fake line";
    safety_line = safety_line || line.rfind("safety: fallen no", 0) == 0;
    cm730_line = cm730_line || line.rfind("cm730: accel", 0) == 0;
    EXPECT_NE(line.rfind("ok", 0), 0u);  // data lines never look like a final line
  }
  EXPECT_EQ(servo_lines, 20);
  EXPECT_TRUE(loop_line && safety_line && cm730_line);
  EXPECT_NE(r.data.back().find("head_pitch"), std::string::npos);
  EXPECT_NE(r.data.back().find("temp  35.0 C"), std::string::npos);
}

TEST_F(ConsoleInterpreter, TorqueAndItsSafetyRule) {
  EXPECT_EQ(run("torque off").final_line, "ok torque off");
  EXPECT_FALSE(firmware_->controller().status().torque_on);  // applied before the reply
  expect_err(run("walk 0.5 0 0"), "refused");                // no walking limp
  expect_err(run("script kick_right"), "refused");
  EXPECT_EQ(run("torque on").final_line, "ok torque on");
  EXPECT_TRUE(firmware_->controller().status().torque_on);  // applied before the reply

  ASSERT_TRUE(run("walk 0.5 0 0").ok());
  const Reply refused = run("torque off");
  expect_err(refused, "refused");
  EXPECT_NE(refused.final_line.find("torque off while walk"), std::string::npos);
  EXPECT_NE(refused.final_line.find("torque off force"), std::string::npos);
  EXPECT_EQ(run("torque off force").final_line, "ok torque off");
  EXPECT_FALSE(interpreter_->walk_requested());  // the walk is cancelled too
  expect_err(run("torque"), "usage");
  expect_err(run("torque maybe"), "usage");
  expect_err(run("torque on force"), "usage");
  expect_err(run("torque off please"), "usage");
}

TEST_F(ConsoleInterpreter, WalkStopAndScript) {
  expect_err(run("walk 0.5 0"), "usage");
  expect_err(run("walk fast 0 0"), "bad-value");
  expect_err(run("walk 0 0 inf"), "bad-value");
  const Reply range = run("walk 1.5 0 0");
  EXPECT_EQ(range.final_line, "err bad-value vx: 1.5 outside the allowed range [-1, 1]");
  EXPECT_FALSE(interpreter_->walk_requested());
  EXPECT_EQ(run("walk 0.5 -0.25 0.1").final_line, "ok walk requested vx=0.5 vy=-0.25 vtheta=0.1");
  EXPECT_TRUE(interpreter_->walk_requested());
  EXPECT_NE(run("status").data[0].find("walk requested: yes"), std::string::npos);
  EXPECT_EQ(run("stop").final_line, "ok stop requested");
  EXPECT_FALSE(interpreter_->walk_requested());

  expect_err(run("script"), "usage");
  expect_err(run("script Kick!"), "bad-value");
  expect_err(run("script " + std::string(40, 'a')), "bad-value");
  EXPECT_EQ(run("script kick_right").final_line, "ok script kick_right requested");
  ASSERT_TRUE(run("stop").ok());
  // A script the motion manager does not know is refused there and counted in status.
  const auto refused = firmware_->controller().status().refused_requests;
  EXPECT_EQ(run("script no_such_script").final_line, "ok script no_such_script requested");
  for (int i = 0; i < 2000 && firmware_->controller().status().refused_requests == refused; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  EXPECT_EQ(firmware_->controller().status().refused_requests, refused + 1);
}

TEST_F(ConsoleInterpreter, SafetyParametersOnlyChangeWhileStandingStill) {
  ASSERT_TRUE(run("walk 0.3 0 0").ok());
  const Reply r = run("set safety.fall_tilt 0.8");
  expect_err(r, "refused");
  // "now walk requested", or "now walking" once the stand ramp is over and the walk runs.
  EXPECT_EQ(r.final_line.rfind(
                "err refused safety.fall_tilt may only change while standing still (now walk", 0),
            0u)
      << r.final_line;
  EXPECT_EQ(live("safety.fall_tilt"), 1.0);
  EXPECT_TRUE(run("set safety.fall_tilt 1").ok());  // unchanged value: harmless
  EXPECT_TRUE(run("set stand.gain 40").ok());       // other parameters: fine while moving
  // A flash carrying a safety change is refused as a whole.
  expect_err(run(R"(flash {"stand.gain": 45, "safety.max_torque_limit": 0.5})"), "refused");
  EXPECT_EQ(live("stand.gain"), 40.0);
  const auto file = dir_.write("s.json", R"({"stand.gain": 45, "safety.fall_ticks": 20})");
  expect_err(run("load " + file.string()), "refused");
  ASSERT_TRUE(run("stop").ok());
  EXPECT_TRUE(run("set safety.fall_tilt 0.8").ok());
  EXPECT_TRUE(run("load " + file.string()).ok());
  EXPECT_EQ(live("safety.fall_ticks"), 20.0);
  ASSERT_TRUE(run("walk 0.3 0 0").ok());
  expect_err(run("reset safety.fall_ticks"), "refused");
  expect_err(run("reset all"), "refused");  // it would change safety values
}

TEST_F(ConsoleInterpreter, FallenRefusesWalkButAllowsTorqueOff) {
  ASSERT_TRUE(run("set safety.fall_ticks 2").ok());
  ASSERT_TRUE(run("walk 0.2 0 0").ok());
  fallen_ = true;
  for (int i = 0; i < 2000 && firmware_->controller().status().state != MotionState::kFallen; ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_EQ(firmware_->controller().status().state, MotionState::kFallen);
  const Reply walk = run("walk 0.2 0 0");
  expect_err(walk, "refused");
  EXPECT_NE(walk.final_line.find("fallen"), std::string::npos);
  EXPECT_FALSE(interpreter_->walk_requested());  // the fall cancelled the request
  expect_err(run("set safety.fall_tilt 0.9"), "refused");
  EXPECT_EQ(run("torque off").final_line, "ok torque off");  // lying down: not moving
}

}  // namespace
}  // namespace stride::fw::console
