// SwingClearance: how high the swing foot rises over the grass, step by step, from the
// simulator's ground truth (issue 29: the soft identified servos let a swing foot graze the grass).
//
// Each foot's lowest stud height is its ankle height less 0.0565 m (the stud tips below the
// ankle crossing, level foot), measured against where the foot stood in the first 0.5 s. A foot
// more than 5 mm above its standing height (and higher than the other) swings; its step ends
// when it is back within 2 mm. Per step: the highest it rose (the clearance), and whether it
// touched the grass at that highest point (grazing).
#pragma once

#include <vector>

#include "stride/sim_hal/sim_world.hpp"

namespace stride::sim {

class SwingClearance {
 public:
  /// One sample; `time_s` from the episode start.
  void observe(double time_s, const GroundTruth& truth);

  /// The clearance of every finished step [m].
  const std::vector<double>& clearance() const noexcept { return clearance_; }
  int steps() const noexcept { return static_cast<int>(clearance_.size()); }
  int grazing_steps() const noexcept { return grazing_; }

 private:
  double stand_left_ = 0.0, stand_right_ = 0.0;
  int swing_ = 0;  // +1 left foot up, -1 right foot up, 0 none
  double peak_ = 0.0;
  bool touching_at_peak_ = false;
  std::vector<double> clearance_;
  int grazing_ = 0;
};

}  // namespace stride::sim
