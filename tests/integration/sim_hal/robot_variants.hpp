// The robots of sim_hal/models/make_variants.py (issue 20), written into a directory for the
// tests that load them: their names, in the script's order, and the call that writes them.
#pragma once

#include <array>
#include <filesystem>
#include <string>

#include "run_command.hpp"

namespace stride::test {

inline constexpr std::array<const char*, 8> kRobotVariants{
    "trunk_mass_plus_10pct",  "trunk_mass_minus_10pct", "trunk_com_1cm_forward",
    "trunk_com_1cm_backward", "trunk_com_1cm_left",     "trunk_com_1cm_right",
    "left_leg_plus_5pct",     "right_leg_plus_5pct"};

/// Runs make_variants.py into `dir` (<name>.urdf each); returns its output, `code` its exit code.
inline std::string write_robot_variants(const std::filesystem::path& dir, int& code) {
  return run_command("python3 " + std::string(STRIDE_SOURCE_DIR) +
                         "/sim_hal/models/make_variants.py " + dir.string(),
                     code);
}

}  // namespace stride::test
