// The kick task's own settings (kick_task.cpp parses and writes them: config fields `script`,
// `kick_at_s`, `yaw_drift_limit_rad`), held in TaskConfig::own.
#pragma once

#include <string>

namespace stride::opt {

struct KickSettings {
  std::string script = "kick_right";  ///< the firmware's kick script (kick_left: the left foot)
  double kick_at_s = 1.0;             ///< when the kick is requested, in [0, duration_s)
  double yaw_drift_limit_rad = 6.66;  ///< constraint (seed: |integral of gyro z| > 6.66)
  bool operator==(const KickSettings&) const = default;
};

}  // namespace stride::opt
