// The unmodified stride-fw with the serial HAL drives the simulated robot over the Dynamixel
// wire protocol: `stride vbus --sim` serves the bus from the Simbody world on a
// pseudo-terminal, advancing one control period per SYNC_WRITE/BULK_READ cycle.
#include <signal.h>

#include <chrono>
#include <thread>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "temp_dir.hpp"

namespace stride::test {
namespace {

const std::string kBin = STRIDE_BIN_DIR;

TEST(VirtualBusSim, FirmwareOverTheWireStandsTheSimulatedRobot) {
  TempDir dir;
  const auto link = dir.path() / "bus";
  const pid_t vbus =
      spawn({kBin + "/stride", "vbus", "--link", link.string(), "--sim", "--seed", "3", "--json"},
            dir.path() / "vbus.out", dir.path() / "vbus.err");
  ASSERT_GT(vbus, 0);
  for (int i = 0; i < 500 && !std::filesystem::exists(link); ++i) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_TRUE(std::filesystem::exists(link)) << slurp(dir.path() / "vbus.err");

  const int ticks = 500;  // 5 s: the stand ramp (1.5 s) and 3.5 s of holding the pose
  const pid_t fw = spawn({kBin + "/stride-fw", "--hal", "serial", "--port", link.string(),
                          "--ticks", std::to_string(ticks), "--bus-margin-us", "4000", "--json"},
                         dir.path() / "fw.out", dir.path() / "fw.err");
  ASSERT_EQ(wait_exit(fw), 0) << slurp(dir.path() / "fw.err");
  kill(vbus, SIGINT);
  ASSERT_EQ(wait_exit(vbus), 0) << slurp(dir.path() / "vbus.err");

  const auto firmware = nlohmann::json::parse(slurp(dir.path() / "fw.out"));
  const auto bus = nlohmann::json::parse(slurp(dir.path() / "vbus.out"));
  EXPECT_EQ(firmware["cycles"], ticks);
  EXPECT_EQ(firmware["motion_state"], "stand");
  EXPECT_FALSE(firmware["fallen"].get<bool>());
  // At most 1 % of the cycles lost, per device: one late cycle (the test shares 2 cores with
  // the other integration tests) times out all 21 devices at once.
  ASSERT_EQ(firmware["bus"]["devices"].size(), 21U);
  for (const auto& device : firmware["bus"]["devices"]) {
    EXPECT_LE(device["timeouts"].get<int>(), ticks / 100) << device["name"] << "\n"
                                                          << slurp(dir.path() / "fw.err");
  }
  EXPECT_EQ(bus["bad_packets"], 0);
  // The world advanced exactly one period per BULK_READ and is still healthy and upright.
  ASSERT_TRUE(bus.contains("sim")) << bus.dump();
  EXPECT_EQ(bus["sim"]["ticks"], bus["bulk_reads"]);
  EXPECT_EQ(bus["sim"]["status"], "running") << bus["sim"]["failure_reason"];
  EXPECT_NEAR(bus["sim"]["sim_time_s"].get<double>(), bus["bulk_reads"].get<double>() * 0.01, 1e-9);
  EXPECT_GT(bus["sim"]["torso_height_m"].get<double>(), 0.45) << "the robot is not standing";
}

TEST(VirtualBusSim, SimNeedsProtocolOne) {
  TempDir dir;
  const pid_t vbus = spawn(
      {kBin + "/stride", "vbus", "--link", (dir.path() / "b").string(), "--sim", "--protocol", "2"},
      dir.path() / "o", dir.path() / "e");
  EXPECT_EQ(wait_exit(vbus), 2);
  EXPECT_NE(slurp(dir.path() / "e").find("--sim"), std::string::npos);
}

}  // namespace
}  // namespace stride::test
