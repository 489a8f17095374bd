// Console server over real pseudo-terminals: echo, prompt and replies on the wire, line
// editing, binary noise and overlong lines, exclusive open, and reopening after the peer
// closed the port (with back-off, no spinning while the device is absent).
#include "stride/firmware/console/console_server.hpp"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <memory>
#include <random>
#include <thread>

#include <gtest/gtest.h>

#include "pseudo_terminal.hpp"
#include "stride/firmware/console/tty_port.hpp"
#include "stride/firmware/firmware.hpp"
#include "stride/hal/scripted_robot.hpp"
#include "temp_dir.hpp"

namespace stride::fw::console {
namespace {

using namespace std::chrono_literals;

bool has_banner(const std::string& r) {
  return r.find("type help\r\n> ") != std::string::npos;
}

class ConsoleServerPty : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(Firmware::create({}, firmware_));
    ticker_ = std::thread([this] {
      hal::Tick tick = 0;
      const auto frame = hal::ScriptedRobot::standing_frame();
      while (!stop_.load()) {
        firmware_->params().apply_staged();
        (void)firmware_->controller().step(frame, tick++);
        std::this_thread::sleep_for(1ms);
      }
    });
  }
  void TearDown() override {
    if (server_) server_->stop();
    stop_ = true;
    if (ticker_.joinable()) ticker_.join();
  }
  void start(const std::string& device, ServerOptions options = {}) {
    ConsoleContext context;
    context.params = &firmware_->params();
    context.controller = &firmware_->controller();
    server_ = make_console(device, context, options);
    server_->start();
  }
  static void wait_banner(test::PseudoTerminal& pty) {
    std::string received;
    ASSERT_TRUE(pty.read_until(received, has_banner, 3s)) << received;
  }

  std::unique_ptr<Firmware> firmware_;
  std::unique_ptr<ConsoleServer> server_;
  std::thread ticker_;
  std::atomic<bool> stop_{false};
};

TEST_F(ConsoleServerPty, EchoReplyAndPromptOnTheWire) {
  test::PseudoTerminal pty;
  start(pty.slave_path());
  wait_banner(pty);
  EXPECT_EQ(pty.command("get stand.gain"), "get stand.gain\r\nok stand.gain = 30\r\n> ");
  EXPECT_EQ(pty.command("set stand.gain 200"),
            "set stand.gain 200\r\nerr bad-value stand.gain: 200 outside the allowed range [5, "
            "100]\r\n> ");
  const std::string list = pty.command("list stand");
  EXPECT_EQ(test::final_line_of(list), "ok 2 parameters");
  EXPECT_NE(list.find("\r\nstand.ramp_time = 1.5 s"), std::string::npos);
  EXPECT_EQ(server_->counters().lines.load(), 3u);
  EXPECT_EQ(server_->counters().errors.load(), 1u);
}

TEST_F(ConsoleServerPty, LineEndingsAndEditing) {
  test::PseudoTerminal pty;
  start(pty.slave_path());
  wait_banner(pty);
  std::string received;
  ASSERT_TRUE(pty.write("get stand.gainn\x7f\r\nget loop.rate_hz\nget motion.get_up\r"));
  ASSERT_TRUE(pty.read_until(
      received,
      [](const std::string& r) { return r.find("get_up = true\r\n> ") != std::string::npos; }, 3s))
      << received;
  // Three lines, three replies (CRLF is one line end), DEL erased the extra 'n'.
  EXPECT_EQ(received,
            "get stand.gainn\b \b\r\nok stand.gain = 30\r\n> get loop.rate_hz\r\nok loop.rate_hz "
            "= 100\r\n> get motion.get_up\r\nok motion.get_up = true\r\n> ");
  // Empty line: a new prompt only. Ctrl-C: the line is abandoned.
  received.clear();
  ASSERT_TRUE(pty.write("\rset stand.gain 99\x03"));
  ASSERT_TRUE(pty.read_until(
      received, [](const std::string& r) { return r.find("^C\r\n> ") != std::string::npos; }, 3s));
  EXPECT_EQ(received, "\r\n> set stand.gain 99^C\r\n> ");
  EXPECT_EQ(test::final_line_of(pty.command("get stand.gain")), "ok stand.gain = 30");
}

TEST_F(ConsoleServerPty, SurvivesBinaryNoiseAndOverlongLines) {
  test::PseudoTerminal pty;
  ServerOptions options;
  options.max_line = 1024;
  start(pty.slave_path(), options);
  wait_banner(pty);
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> byte(0, 255);
  std::string noise(64 * 1024, '\0');
  for (char& c : noise) c = static_cast<char>(byte(rng));
  // The server's echo is drained while the noise goes in (a full pty would stop it), until it
  // reports the overlong line written after the noise: it has then read all of the noise, on a
  // loaded host too (a fixed wait of 300 ms was not always enough under ASan).
  const std::string overlong = "err line-too-long line longer than 1024 bytes discarded";
  std::string discarded;
  std::thread drain([&] {
    const auto deadline = std::chrono::steady_clock::now() + 20s;
    while (discarded.find(overlong) == std::string::npos &&
           std::chrono::steady_clock::now() < deadline)
      (void)pty.read_for(discarded, 20ms);
  });
  EXPECT_TRUE(pty.write(noise));  // EXPECT: the drain is joined whatever happens
  EXPECT_TRUE(pty.write(std::string(5000, 'x') + "\r"));
  drain.join();
  EXPECT_NE(discarded.find(overlong), std::string::npos);
  EXPECT_GE(server_->counters().overlong_lines.load(), 1u);
  EXPECT_GT(server_->counters().noise_bytes.load(), 10000u);
  // After the noise a Ctrl-C clears any partial line and the console answers normally.
  ASSERT_TRUE(pty.write("\x03"));
  std::this_thread::sleep_for(100ms);
  std::string rest;
  (void)pty.read_for(rest, 50ms);
  EXPECT_EQ(test::final_line_of(pty.command("set stand.gain 45")), "ok stand.gain = 45");
  double v = 0;
  ASSERT_TRUE(firmware_->params().get("stand.gain", v));
  EXPECT_EQ(v, 45.0);
}

TEST_F(ConsoleServerPty, OpensExclusively) {
  test::PseudoTerminal pty;
  start(pty.slave_path());
  wait_banner(pty);
  TtyPort second;
  const Status s = second.open(pty.slave_path(), 115200);
  ASSERT_FALSE(s);
  EXPECT_NE(s.message().find("in use"), std::string::npos) << s.message();
}

TEST_F(ConsoleServerPty, ReopensAfterThePeerClosesWithBackOff) {
  test::TempDir dir;
  const auto link = dir.path() / "console";
  auto pty = std::make_unique<test::PseudoTerminal>();
  std::filesystem::create_symlink(pty->slave_path(), link);
  start(link.string());
  wait_banner(*pty);
  EXPECT_EQ(test::final_line_of(pty->command("set stand.gain 41")), "ok stand.gain = 41");

  // The peer goes away and the device is absent for a second.
  pty->close_master();
  pty.reset();
  std::filesystem::remove(link);
  const auto failed_before = server_->counters().failed_opens.load();
  std::this_thread::sleep_for(1000ms);
  const auto attempts = server_->counters().failed_opens.load() - failed_before;
  EXPECT_GE(server_->counters().link_losses.load(), 1u);
  EXPECT_LE(attempts, 8u) << "reopen must back off, not spin";

  // A new port appears at the same path: the console comes back on its own.
  pty = std::make_unique<test::PseudoTerminal>();
  std::filesystem::create_symlink(pty->slave_path(), link);
  wait_banner(*pty);
  EXPECT_EQ(test::final_line_of(pty->command("get stand.gain")), "ok stand.gain = 41");
  EXPECT_EQ(server_->counters().opens.load(), 2u);
}

TEST_F(ConsoleServerPty, MissingDeviceIsRetriedQuietly) {
  start("/nonexistent/stride-console");
  std::this_thread::sleep_for(500ms);
  const auto attempts = server_->counters().failed_opens.load();
  EXPECT_GE(attempts, 2u);
  EXPECT_LE(attempts, 6u);  // 50, 100, 200 ms ... back-off
  server_->stop();
  EXPECT_TRUE(server_->finished());
}

}  // namespace
}  // namespace stride::fw::console
