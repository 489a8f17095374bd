// A heading hold fed as the walk engines feed it (tests only): the firmware's attitude estimate
// updated with the tick's IMU first, then the hold. Shared by the heading-hold and the
// magnetic-heading tests.
#pragma once

#include "stride/firmware/attitude_estimator.hpp"
#include "stride/firmware/parameter_store.hpp"
#include "stride/firmware/walk/heading_hold.hpp"
#include "stride/hal/sensor_frame.hpp"

namespace stride::fw::test {

struct FedHeadingHold {
  FedHeadingHold(ParameterStore& store, double period_s)
      : attitude(store, period_s), hold(store, period_s) {}
  AttitudeEstimator attitude;
  walk::HeadingHold hold;
  void update(const hal::Cm730State& imu, bool calibrating, bool holding) {
    attitude.update(imu);
    hold.update(attitude, imu, calibrating, holding);
  }
};

}  // namespace stride::fw::test
