// stride-fw --record end to end on the test HAL: every tick read back by the C++ reader and by
// firmware/tools/read_flight_log.py, parameter values from --params in the header and changes
// from the console in the ticks, a SIGKILLed run that still reads, and a bad --record path.
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "pseudo_terminal.hpp"
#include "run_command.hpp"
#include "stride/firmware/recorder/flight_log_format.hpp"
#include "stride/firmware/recorder/flight_log_header.hpp"
#include "stride/firmware/recorder/flight_log_reader.hpp"
#include "stride/firmware/servo_table.hpp"
#include "temp_dir.hpp"

namespace stride::test {
namespace {

using namespace std::chrono_literals;

const std::string kBin = STRIDE_BIN_DIR;
const std::string kReadScript =
    std::string(STRIDE_SOURCE_DIR) + "/firmware/tools/read_flight_log.py";

nlohmann::json last_json_line(const std::string& out) {
  const auto brace = out.rfind("\n{");
  return nlohmann::json::parse(brace == std::string::npos ? out : out.substr(brace + 1));
}

// The Python reader's summary of a log, or null if python3 is not there.
nlohmann::json python_summary(const std::filesystem::path& log) {
  int code = -1;
  (void)run_command("python3 --version >/dev/null 2>&1", code);
  if (code != 0) return nullptr;
  const std::string out =
      run_command("python3 " + kReadScript + " " + log.string() + " --json", code);
  EXPECT_EQ(code, 0) << out;
  return nlohmann::json::parse(out);
}

void expect_ticks_increase(const fw::FlightLog& log) {
  for (std::size_t i = 1; i < log.ticks.size(); ++i) {
    ASSERT_GT(log.ticks[i].meta.tick, log.ticks[i - 1].meta.tick) << i;
    ASSERT_EQ(log.ticks[i].commands.tick, log.ticks[i].meta.tick) << i;
  }
}

TEST(FlightRecorderCli, EveryTickOfATestHalRunWithTheParameterFileInTheHeader) {
  TempDir dir;
  const auto params = dir.write("p.json", R"({"stand": {"gain": 50}})");
  const auto log_path = dir.path() / "run.flog";
  const int code =
      wait_exit(spawn({kBin + "/stride-fw", "--hal", "test", "--ticks", "200", "--no-rt", "--json",
                       "--params", params.string(), "--record", log_path.string()},
                      dir.path() / "out", dir.path() / "err"));
  ASSERT_EQ(code, 0) << slurp(dir.path() / "err");
  const auto report = nlohmann::json::parse(slurp(dir.path() / "out"));
  EXPECT_EQ(report["record"]["ticks_recorded"], 200);
  EXPECT_EQ(report["record"]["ticks_dropped"], 0);
  EXPECT_EQ(report["record"]["bytes"], std::filesystem::file_size(log_path));

  fw::FlightLog log;
  const Status s = fw::read_flight_log(log_path, log);
  ASSERT_TRUE(s) << s.message();
  EXPECT_TRUE(log.has_end);
  EXPECT_EQ(log.stopped_early, "");
  ASSERT_EQ(log.ticks.size(), 200u);
  EXPECT_EQ(log.ticks.front().meta.tick, 0);
  expect_ticks_increase(log);
  EXPECT_EQ(log.header["hal"], "test");
  EXPECT_EQ(log.header["period_ns"], 10'000'000);
  EXPECT_EQ(log.header["params_file"], params.string());
  EXPECT_EQ(log.header["robot_description"]["hash"],
            fw::flight_log::robot_description_hash(fw::ServoTable::defaults(),
                                                   fw::RobotDescription::defaults()));
  const int gain = log.parameter_index("stand.gain");
  ASSERT_GE(gain, 0);
  EXPECT_EQ(log.header["parameters"][gain]["value"], 50.0);  // from --params
  EXPECT_EQ(log.header["parameters"][gain]["default"], 30.0);
  EXPECT_EQ(log.ticks.back().commands.servos[0].p_gain, 127.0);  // stand.gain 50 ran
  EXPECT_EQ(log.header["motion_states"][static_cast<int>(log.ticks.back().meta.motion)],
            report["motion_state"]);

  const nlohmann::json py = python_summary(log_path);
  if (py.is_null()) GTEST_SKIP() << "python3 not installed: the Python reader was not run";
  EXPECT_EQ(py["ticks"], 200);
  EXPECT_EQ(py["last_tick"], log.ticks.back().meta.tick);
  EXPECT_EQ(py["stopped"], nullptr);
  EXPECT_EQ(py["end"]["ticks_recorded"], 200);
  EXPECT_EQ(py["robot_description_hash"], log.header["robot_description"]["hash"]);
  EXPECT_EQ(py["last_motion"], report["motion_state"]);
  ASSERT_EQ(py["last_command_positions"].size(), 20u);
  for (std::size_t i = 0; i < 20; ++i) {
    EXPECT_EQ(py["last_command_positions"][i].get<double>(),
              log.ticks.back().commands.servos[i].position_rad)
        << i;
  }
}

TEST(FlightRecorderCli, ConsoleParameterChangesAreRecordedAtTheTickTheyApplied) {
  TempDir dir;
  PseudoTerminal pty;
  const auto log_path = dir.path() / "run.flog";
  const pid_t pid = spawn({kBin + "/stride-fw", "--hal", "test", "--no-rt", "--json", "--console",
                           pty.slave_path(), "--record", log_path.string()},
                          dir.path() / "out", dir.path() / "err");
  ASSERT_GT(pid, 0);
  std::string received;
  ASSERT_TRUE(pty.read_until(
      received, [](const std::string& r) { return r.find("type help") != std::string::npos; }, 30s))
      << received << slurp(dir.path() / "err");
  std::this_thread::sleep_for(300ms);
  EXPECT_EQ(final_line_of(pty.command("set stand.gain 50")), "ok stand.gain = 50");
  EXPECT_EQ(final_line_of(pty.command(R"(flash {"motion":{"fallen_gain":6}})")),
            "ok flashed 1 parameters");
  std::this_thread::sleep_for(200ms);
  ::kill(pid, SIGINT);
  ASSERT_EQ(wait_exit(pid), 0) << slurp(dir.path() / "err");
  const auto report = last_json_line(slurp(dir.path() / "out"));

  fw::FlightLog log;
  ASSERT_TRUE(fw::read_flight_log(log_path, log));
  EXPECT_TRUE(log.has_end);
  EXPECT_EQ(log.ticks.size(), report["cycles"].get<std::size_t>());
  expect_ticks_increase(log);
  const int gain = log.parameter_index("stand.gain");
  const int fallen_gain = log.parameter_index("motion.fallen_gain");
  std::vector<std::size_t> gain_at, fallen_gain_at;
  for (std::size_t i = 0; i < log.ticks.size(); ++i) {
    for (const auto& change : log.ticks[i].param_changes) {
      if (change.handle == static_cast<fw::ParamHandle>(gain)) {
        EXPECT_EQ(change.value, 50.0);
        gain_at.push_back(i);
      }
      if (change.handle == static_cast<fw::ParamHandle>(fallen_gain)) {
        EXPECT_EQ(change.value, 6.0);
        fallen_gain_at.push_back(i);
      }
    }
  }
  ASSERT_EQ(gain_at.size(), 1u);
  ASSERT_EQ(fallen_gain_at.size(), 1u);
  EXPECT_LT(gain_at[0], fallen_gain_at[0]);
  // The tick that applied stand.gain already sent the new P gain (30 -> 76, 50 -> 127).
  ASSERT_GT(gain_at[0], 0u);
  EXPECT_EQ(log.ticks[gain_at[0] - 1].commands.servos[0].p_gain, 76.0);
  EXPECT_EQ(log.ticks[gain_at[0]].commands.servos[0].p_gain, 127.0);

  const nlohmann::json py = python_summary(log_path);
  if (py.is_null()) GTEST_SKIP() << "python3 not installed: the Python reader was not run";
  ASSERT_EQ(py["param_changes"].size(), 2u);
  EXPECT_EQ(py["param_changes"][0][0], log.ticks[gain_at[0]].meta.tick);
  EXPECT_EQ(py["param_changes"][0][1], "stand.gain");
  EXPECT_EQ(py["param_changes"][0][2], 50.0);
  EXPECT_EQ(py["param_changes"][1][1], "motion.fallen_gain");
}

TEST(FlightRecorderCli, AKilledStrideFwLeavesALogThatReadsToItsLastCompleteBlock) {
  TempDir dir;
  // The header holds every parameter, so its size grows with the scripts: measure it (a log of
  // one tick) and wait for about 150 ticks more.
  const auto one_tick = dir.path() / "one.flog";
  int code = -1;
  run_command(kBin + "/stride-fw --hal test --ticks 1 --no-rt --record " + one_tick.string() +
                  " >/dev/null 2>&1",
              code);
  ASSERT_EQ(code, 0);
  // A tick without parameter changes is one block: its head, the tick's fixed payload, its tail.
  constexpr std::size_t kTickBlockBytes = fw::flight_log::kBlockHeadBytes +
                                          fw::flight_log::kTickFixedBytes +
                                          fw::flight_log::kBlockTailBytes;
  const auto wait_for_bytes = std::filesystem::file_size(one_tick) + 150 * kTickBlockBytes;
  const auto log_path = dir.path() / "run.flog";
  const pid_t pid =
      spawn({kBin + "/stride-fw", "--hal", "test", "--no-rt", "--record", log_path.string()},
            dir.path() / "out", dir.path() / "err");
  ASSERT_GT(pid, 0);
  // Wait for about 1.5 s of ticks on disk (the test HAL runs at 100 Hz on the clock).
  const auto bytes_on_disk = [&] {
    std::error_code error;
    const auto size = std::filesystem::file_size(log_path, error);
    return error ? 0 : size;
  };
  for (int i = 0; i < 1000 && bytes_on_disk() < wait_for_bytes; ++i) {
    std::this_thread::sleep_for(10ms);
  }
  ::kill(pid, SIGKILL);
  EXPECT_EQ(wait_exit(pid), 128 + SIGKILL);

  fw::FlightLog log;
  const Status s = fw::read_flight_log(log_path, log);
  ASSERT_TRUE(s) << s.message();
  EXPECT_FALSE(log.has_end);
  EXPECT_GE(log.ticks.size(), 100u);
  EXPECT_EQ(log.ticks.front().meta.tick, 0);
  expect_ticks_increase(log);
  EXPECT_EQ(log.dropped_ticks(), 0u);
  // The reader stops exactly at the end of the last complete block: a cut tail is reported,
  // the file cut there reads the same ticks with nothing left over, and one byte less loses
  // the last tick.
  EXPECT_EQ(log.stopped_early.empty(), log.complete_bytes == log.file_bytes) << log.stopped_early;
  const auto cut = dir.path() / "cut.flog";
  std::filesystem::copy_file(log_path, cut);
  std::filesystem::resize_file(cut, log.complete_bytes);
  fw::FlightLog whole;
  ASSERT_TRUE(fw::read_flight_log(cut, whole));
  EXPECT_EQ(whole.stopped_early, "");
  EXPECT_EQ(whole.file_bytes, log.complete_bytes);
  EXPECT_EQ(whole.complete_bytes, log.complete_bytes);
  EXPECT_EQ(whole.ticks.size(), log.ticks.size());
  std::filesystem::resize_file(cut, log.complete_bytes - 1);
  fw::FlightLog short_by_one;
  ASSERT_TRUE(fw::read_flight_log(cut, short_by_one));
  EXPECT_NE(short_by_one.stopped_early, "");
  EXPECT_EQ(short_by_one.ticks.size(), log.ticks.size() - 1);
  EXPECT_LT(short_by_one.complete_bytes, log.complete_bytes);
  RecordProperty("ticks_before_kill", static_cast<int>(log.ticks.size()));

  const nlohmann::json py = python_summary(log_path);
  if (py.is_null()) GTEST_SKIP() << "python3 not installed: the Python reader was not run";
  EXPECT_EQ(py["ticks"].get<std::size_t>(), log.ticks.size());
  EXPECT_EQ(py["end"], nullptr);
}

TEST(FlightRecorderCli, AnUnwritableRecordPathIsOneLineAndExit2) {
  int code = -1;
  std::string out = run_command(
      kBin + "/stride-fw --hal test --ticks 5 --no-rt --record /nonexistent-stride/run.flog 2>&1",
      code);
  EXPECT_EQ(code, 2);
  EXPECT_EQ(out,
            "stride-fw: --record: cannot open '/nonexistent-stride/run.flog' for writing: No such "
            "file or directory\n");
  out = run_command(kBin + "/stride-fw --hal test --ticks 5 --record-buffer-kb 1 2>&1", code);
  EXPECT_EQ(code, 2);
  EXPECT_EQ(out, "stride-fw: --record-buffer-kb: must be in [4, 4194304], got 1\n");
}

}  // namespace
}  // namespace stride::test
