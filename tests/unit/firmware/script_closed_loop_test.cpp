// Scripts that close the loop (issue 54 point 1): a frame's wait holds it at its deadline until
// the trunk's pitch (the attitude estimate) is in its band, moving the later frames back; a wait
// that times out and a guard that trips abort the script; the values are parameters; the file
// format reads and writes them and names a bad one; a player without an estimate plays as timed.
#include <cmath>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "stride/firmware/attitude_estimator.hpp"
#include "stride/firmware/script/script_engine.hpp"
#include "stride/hal/scripted_robot.hpp"

namespace stride::fw {
namespace {

constexpr std::int64_t kPeriodNs = 10'000'000;  // 100 Hz
std::size_t idx(const char* name) {
  return *ServoTable::defaults().index_of(name);
}

// Frame 1 (100 ms) r_knee -> 1.0 with a wait for pitch in [-0.2, 0.2] (timeout 300 ms); frame 2
// (50 ms) r_knee -> 0.4 with a guard of [-0.5, 0.5].
Script waiting_script() {
  Script s;
  s.name = "probe";
  ScriptFrame one{100, {{idx("r_knee"), 1.0, 100, 100}}, {}, {}};
  one.wait = {true, -0.2, 0.2, 1.0, 300};
  ScriptFrame two{50, {{idx("r_knee"), 0.4, 100, 100}}, {}, {}};
  two.guard = {true, -0.5, 0.5};
  s.frames = {one, two};
  return s;
}

struct Fixture {
  ParameterStore params;
  AttitudeEstimator attitude{0.01, 0.5, false};
  ScriptEngine engine{kPeriodNs, params, ServoTable::defaults(), &attitude};
  hal::SensorFrame sensors = hal::ScriptedRobot::standing_frame();
  hal::CommandFrame out{};

  Fixture() {
    const Status status = engine.add_script(waiting_script());
    if (!status) ADD_FAILURE() << status.message();
    EXPECT_TRUE(engine.select(engine.find("probe")));
    lean(0.0);
  }
  /// The trunk pitched by `pitch` [rad] (nose down positive), turning at `rate` about y.
  void lean(double pitch, double rate = 0.0) {
    const Eigen::Vector3d f(-9.81 * std::sin(pitch), 0.0, 9.81 * std::cos(pitch));
    attitude.update(f, Eigen::Vector3d(0.0, rate, 0.0));
    attitude.start(f);  // exactly this pitch; the gyro reading stays
  }
  void step(hal::Tick tick) { engine.step(sensors, tick, out); }
};

TEST(ScriptClosedLoop, AWaitHoldsTheFrameUntilThePitchIsInItsBandAndMovesTheRestBack) {
  Fixture f;
  f.engine.start(f.sensors, f.out, 0);
  ASSERT_EQ(f.engine.deadline(0), 10);
  ASSERT_EQ(f.engine.deadline(1), 15);
  f.lean(0.6);  // leaning too far: frame 1 is held past its deadline
  for (hal::Tick t = 0; t <= 20; ++t) f.step(t);
  EXPECT_EQ(f.out.servos[idx("r_knee")].position_rad, 1.0);  // still frame 1's target
  EXPECT_FALSE(f.engine.done());
  EXPECT_FALSE(f.engine.aborted());
  EXPECT_EQ(f.engine.deadline(0), 21);  // one tick ahead while held
  EXPECT_EQ(f.engine.deadline(1), 26);  // frame 2 keeps its 50 ms
  f.lean(0.1);                          // in the band: frame 2 starts now and lasts its 50 ms
  f.step(21);
  EXPECT_EQ(f.out.servos[idx("r_knee")].position_rad, 0.4);
  for (hal::Tick t = 22; t < 26; ++t) {
    f.step(t);
    EXPECT_FALSE(f.engine.done()) << t;
  }
  f.step(26);
  EXPECT_TRUE(f.engine.done());
  EXPECT_FALSE(f.engine.aborted());
}

TEST(ScriptClosedLoop, AWaitAlsoNeedsThePitchRateUnderItsLimit) {
  Fixture f;
  f.engine.start(f.sensors, f.out, 0);
  f.lean(0.0, 2.0);  // in the band but pitching at 2 rad/s (limit 1)
  for (hal::Tick t = 0; t <= 12; ++t) f.step(t);
  EXPECT_EQ(f.out.servos[idx("r_knee")].position_rad, 1.0);
  f.lean(0.0, 0.5);
  f.step(13);
  EXPECT_EQ(f.out.servos[idx("r_knee")].position_rad, 0.4);
}

TEST(ScriptClosedLoop, AWaitThatTimesOutAbortsTheScript) {
  Fixture f;
  f.engine.start(f.sensors, f.out, 0);
  f.lean(-1.0);
  for (hal::Tick t = 0; t < 40; ++t) {  // deadline 10, timeout 300 ms = 30 ticks
    f.step(t);
    EXPECT_FALSE(f.engine.aborted()) << t;
  }
  f.step(40);
  EXPECT_TRUE(f.engine.aborted());
  EXPECT_TRUE(f.engine.done());
  // The servos keep the last commands: nothing more is written.
  f.out.servos[idx("r_knee")].position_rad = -7.0;
  f.step(41);
  EXPECT_EQ(f.out.servos[idx("r_knee")].position_rad, -7.0);
  // The next start plays again from the first frame.
  f.lean(0.0);
  f.engine.start(f.sensors, f.out, 50);
  EXPECT_FALSE(f.engine.aborted());
  EXPECT_FALSE(f.engine.done());
}

TEST(ScriptClosedLoop, AGuardThatTripsAbortsTheFrameItGuards) {
  Fixture f;
  f.engine.start(f.sensors, f.out, 0);
  f.lean(0.15);  // frame 1: no guard; its wait is met
  for (hal::Tick t = 0; t <= 11; ++t) f.step(t);
  EXPECT_FALSE(f.engine.aborted());
  f.lean(0.7);  // frame 2's guard is [-0.5, 0.5]
  f.step(12);
  EXPECT_TRUE(f.engine.aborted());
  EXPECT_TRUE(f.engine.done());
}

TEST(ScriptClosedLoop, TheBandsAreParametersReadAtStart) {
  Fixture f;
  const char* name = "script.probe.frame1.wait.pitch_max";
  ASSERT_TRUE(f.params.find(name));
  EXPECT_EQ(f.params.value(*f.params.find(name)), 0.2);
  EXPECT_TRUE(f.params.find("script.probe.frame1.wait.timeout_ms"));
  EXPECT_TRUE(f.params.find("script.probe.frame2.guard.pitch_min"));
  EXPECT_FALSE(f.params.find("script.probe.frame2.wait.pitch_min"));  // frame 2 has no wait
  ASSERT_TRUE(f.params.set_now({{name, 0.8}}));
  f.engine.start(f.sensors, f.out, 0);
  f.lean(0.45);  // outside the file's band, inside the widened one (and frame 2's guard)
  for (hal::Tick t = 0; t <= 10; ++t) f.step(t);
  EXPECT_EQ(f.out.servos[idx("r_knee")].position_rad, 0.4);
}

TEST(ScriptClosedLoop, WithoutAnAttitudeEstimateTheScriptPlaysAsTimed) {
  ParameterStore params;
  ScriptEngine engine{kPeriodNs, params};
  ASSERT_TRUE(engine.add_script(waiting_script()));
  ASSERT_TRUE(engine.select(0));
  hal::SensorFrame sensors = hal::ScriptedRobot::standing_frame();
  hal::CommandFrame out{};
  engine.start(sensors, out, 0);
  for (hal::Tick t = 0; t <= 15; ++t) engine.step(sensors, t, out);
  EXPECT_TRUE(engine.done());
  EXPECT_FALSE(engine.aborted());
}

TEST(ScriptClosedLoop, TheTimeScaleStretchesEveryFrameOfTheNextStart) {
  Fixture f;
  f.engine.set_time_scale(1.5);
  f.engine.start(f.sensors, f.out, 0);
  EXPECT_EQ(f.engine.deadline(0), 15);
  EXPECT_EQ(f.engine.deadline(1), 23);  // round(150 ms x 1.5 / 10 ms) = 22.5 -> 23
  f.engine.set_time_scale(1.0);
  f.engine.start(f.sensors, f.out, 0);
  EXPECT_EQ(f.engine.deadline(1), 15);
}

TEST(ScriptClosedLoop, TheFileReadsAndWritesWaitsAndGuardsAndNamesABadOne) {
  const ServoTable& servos = ServoTable::defaults();
  nlohmann::json doc = {
      {"name", "probe"},
      {"frames",
       {{{"duration_ms", 100},
         {"targets", {{{"servo", "r_knee"}, {"position", 1.0}, {"gain", 50}, {"torque", 100}}}},
         {"wait", {{"pitch_min", -0.87}, {"pitch_max", 1.5}, {"timeout_ms", 200}}},
         {"guard", {{"pitch_min", -1.2}, {"pitch_max", 1.2}}}}}}};
  Script s;
  ASSERT_TRUE(parse_script(doc, "probe.json", servos, s));
  EXPECT_TRUE(s.frames[0].wait.enabled);
  EXPECT_EQ(s.frames[0].wait.pitch_min_rad, -0.87);
  EXPECT_EQ(s.frames[0].wait.rate_max_rad_s, 20.0);  // not given: no rate limit
  EXPECT_EQ(s.frames[0].wait.timeout_ms, 200);
  EXPECT_TRUE(s.frames[0].guard.enabled);
  Script back;
  ASSERT_TRUE(parse_script(script_to_json(s, servos), "again", servos, back));
  EXPECT_EQ(script_to_json(back, servos), script_to_json(s, servos));

  auto error = [&](nlohmann::json bad) {
    Script out;
    const Status status = parse_script(bad, "probe.json", servos, out);
    EXPECT_FALSE(status);
    return status.message();
  };
  nlohmann::json bad = doc;
  bad["frames"][0]["wait"]["pitch_min"] = 1.6;
  EXPECT_EQ(error(bad), "probe.json: frames[0].wait.pitch_min: 1.6 outside [-pi/2, pi/2] rad");
  bad = doc;
  bad["frames"][0]["guard"]["pitch_max"] = -1.5;
  EXPECT_EQ(error(bad), "probe.json: frames[0].guard: pitch_min -1.2 must be below pitch_max -1.5");
  bad = doc;
  bad["frames"][0]["wait"]["timeout_ms"] = 20.5;
  EXPECT_EQ(error(bad),
            "probe.json: frames[0].wait.timeout_ms: must be an integer 0..60000, got 20.5");
  bad = doc;
  bad["frames"][0]["wait"]["pitch"] = 0.1;
  EXPECT_EQ(error(bad), "probe.json: frames[0].wait.pitch: unknown field");
  bad = doc;
  bad["frames"][0]["wait"].erase("timeout_ms");
  EXPECT_EQ(error(bad), "probe.json: frames[0].wait.timeout_ms: missing");
}

}  // namespace
}  // namespace stride::fw
