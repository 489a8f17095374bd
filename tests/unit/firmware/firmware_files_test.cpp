// FirmwareFiles: the data files loaded once build the same firmware as loading them from disk.
#include <filesystem>
#include <fstream>
#include <memory>

#include <gtest/gtest.h>

#include "stride/firmware/firmware.hpp"
#include "stride/hal/scripted_robot.hpp"

namespace stride::fw {
namespace {

TEST(FirmwareFiles, FirmwaresBuiltFromLoadedFilesMatchOnesBuiltFromDisk) {
  FirmwareFiles files;
  ASSERT_TRUE(FirmwareFiles::load({}, files));
  EXPECT_GT(files.scripts.size(), 0u);
  std::unique_ptr<Firmware> from_disk;
  std::unique_ptr<Firmware> from_files;
  ASSERT_TRUE(Firmware::create({}, from_disk));
  ASSERT_TRUE(Firmware::create({}, files, from_files));
  // The same parameters (names, order, values: the scripts' positions are parameters too).
  ASSERT_EQ(from_disk->params().size(), from_files->params().size());
  for (ParamHandle h = 0; h < from_disk->params().size(); ++h) {
    EXPECT_EQ(from_disk->params().spec(h).name, from_files->params().spec(h).name);
    EXPECT_EQ(from_disk->params().value(h), from_files->params().value(h));
  }
  // The same commands, tick for tick, through a walk and a kick request.
  const auto sensors = hal::ScriptedRobot::standing_frame();
  for (Firmware* fw : {from_disk.get(), from_files.get()}) {
    fw->controller().request(MotionRequest::play("kick_right"));
  }
  for (hal::Tick t = 0; t < 200; ++t) {
    const hal::CommandFrame a = from_disk->controller().step(sensors, t);
    const hal::CommandFrame b = from_files->controller().step(sensors, t);
    for (std::size_t i = 0; i < hal::kServoCount; ++i) {
      ASSERT_EQ(a.servos[i].position_rad, b.servos[i].position_rad) << "tick " << t;
    }
  }
  // Two firmwares from one set of files are independent.
  std::unique_ptr<Firmware> second;
  ASSERT_TRUE(Firmware::create({}, files, second));
  ASSERT_TRUE(second->params().set_now({{"walk.stance.body_tilt", 0.2}}));
  double body_tilt = 0;
  ASSERT_TRUE(from_files->params().get("walk.stance.body_tilt", body_tilt));
  EXPECT_EQ(body_tilt, 0.174);
}

TEST(FirmwareFiles, ABrokenScriptFolderIsAnErrorNamingTheFile) {
  const auto folder = std::filesystem::temp_directory_path() / "stride_firmware_files_test";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  std::ofstream(folder / "broken.json") << "{\"name\": \"broken\", \"frames\": [";
  FirmwareOptions options;
  options.scripts_dir = folder;
  FirmwareFiles files;
  const Status s = FirmwareFiles::load(options, files);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("broken.json"), std::string::npos) << s.message();
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace stride::fw
