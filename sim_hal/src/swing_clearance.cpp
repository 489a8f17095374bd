// SwingClearance (see the header).
#include "stride/sim_hal/swing_clearance.hpp"

namespace stride::sim {
namespace {

constexpr double kStudsBelowAnkle = 0.0565;  // stud tips below the ankle crossing [m]
constexpr double kStandingTime = 0.5;        // the standing height is taken before this [s]
constexpr double kLifted = 0.005;            // a foot this far above standing swings [m]
constexpr double kLanded = 0.002;            // and has landed once back within this [m]

}  // namespace

void SwingClearance::observe(double time_s, const GroundTruth& truth) {
  const double left = truth.left_foot.translation().z() - kStudsBelowAnkle;
  const double right = truth.right_foot.translation().z() - kStudsBelowAnkle;
  if (time_s < kStandingTime) {
    stand_left_ = left;
    stand_right_ = right;
    return;
  }
  const double up_left = left - stand_left_, up_right = right - stand_right_;
  if (swing_ == 0) {
    swing_ = up_left > kLifted && up_left > up_right
                 ? 1
                 : (up_right > kLifted && up_right > up_left ? -1 : 0);
    peak_ = 0.0;
    touching_at_peak_ = false;
  }
  if (swing_ == 0) return;
  const double up = swing_ > 0 ? up_left : up_right;
  const FootContact& contact = swing_ > 0 ? truth.left_contact : truth.right_contact;
  if (up > peak_) {
    peak_ = up;
    touching_at_peak_ = contact.points_in_contact > 0;
  }
  if (up < kLanded) {
    clearance_.push_back(peak_);
    if (touching_at_peak_) ++grazing_;
    swing_ = 0;
  }
}

}  // namespace stride::sim
