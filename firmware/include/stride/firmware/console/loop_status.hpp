// Loop statistics for the console's `status` command: cycles, missed ticks, period jitter,
// compute time and bus health, read from the running loop by the console thread.
//
// These are monitoring values: they are read while the control thread updates them, without
// locking (the control thread must never wait for the console), so a line may mix values of
// two consecutive ticks.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "stride/firmware/control_loop.hpp"
#include "stride/firmware/realtime_robot.hpp"
#include "stride/hal/robot.hpp"

namespace stride::fw::console {

/// A `ConsoleContext::loop_status` function for a loop; `paced` may be null (not clock-paced).
std::function<std::vector<std::string>()> loop_status_lines(const ControlLoop& loop,
                                                            const RealtimeRobot* paced,
                                                            const hal::Robot& robot);

}  // namespace stride::fw::console
