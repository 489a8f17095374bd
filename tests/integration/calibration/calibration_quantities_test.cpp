// The calibration quantities (issue 44 point 2): each calibrated value of a world file has one
// name, unit and range (sim::calibration_quantities). The world file reads and writes each
// through its field and refuses it outside its range, SimWorld refuses a world outside it, and
// `stride calibrate --fit` searches within bounds inside it.
#include <cmath>
#include <memory>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "stride/calibration/calibration.hpp"
#include "stride/sim_hal/sim_world.hpp"
#include "stride/sim_hal/world_file.hpp"

namespace stride::sim {
namespace {

TEST(CalibrationQuantities, TheFitSearchesInsideEachRange) {
  const auto& params = calibration::calibration_parameters();
  EXPECT_EQ(params.size(), calibration_quantities().size());  // every quantity is fittable
  for (const calibration::CalibrationParameter& p : params) {
    SCOPED_TRACE(p.name);
    const CalibrationQuantity* q = find_calibration_quantity(p.name);
    ASSERT_NE(q, nullptr);
    EXPECT_EQ(p.unit, q->unit);  // the fit's words are the quantity's
    EXPECT_EQ(p.what, q->what);
    EXPECT_EQ(p.whole, q->whole);
    EXPECT_LT(p.lower, p.upper);
    EXPECT_GE(p.lower, q->min);
    EXPECT_LE(p.upper, q->max);
    EXPECT_GT(p.step, 0.0);
  }
}

TEST(CalibrationQuantities, EachIsItsOwnFieldOfAWorldFile) {
  const WorldFile nominal;
  for (const CalibrationQuantity& q : calibration_quantities()) {
    SCOPED_TRACE(std::string(q.name));
    const double n = q.get(nominal);
    EXPECT_GE(n, q.min);  // the nominal robot is in range
    EXPECT_LE(n, q.max);
    EXPECT_TRUE(check_calibration(nominal));
    // The far end of the range survives the file and moves this value alone.
    const double far = std::abs(q.max - n) >= std::abs(q.min - n) ? q.max : q.min;
    WorldFile w;
    q.set(w, far);
    ASSERT_EQ(q.get(w), far);
    for (const CalibrationQuantity& other : calibration_quantities())
      if (other.name != q.name) {
        EXPECT_EQ(other.get(w), other.get(nominal)) << other.name;
      }
    WorldFile back;
    ASSERT_TRUE(parse_world_file(to_json(w), back));
    EXPECT_EQ(q.get(back), far);
    EXPECT_TRUE(check_calibration(back));
    // Beyond the range: the file names the field, SimWorld and check_calibration the value.
    const double beyond = far + (far == q.max ? 1.0 : -1.0);
    q.set(w, beyond);
    nlohmann::json doc = to_json(w);
    const Status read = parse_world_file(doc, back);
    ASSERT_FALSE(read);
    std::string field(q.field);
    field = field.substr(0, field.find('['));
    EXPECT_EQ(read.message().rfind(field + ": must be", 0), 0u) << read.message();
    const Status checked = check_calibration(w);
    ASSERT_FALSE(checked);
    EXPECT_NE(checked.message().find(std::string(q.what) + " must be in"), std::string::npos)
        << checked.message();
    WorldOptions options;
    options.ball.present = false;
    w.apply_calibration(options);
    std::unique_ptr<SimWorld> world;
    const Status created = SimWorld::create(options, ResetSpec::standing(), world);
    ASSERT_FALSE(created);
    EXPECT_EQ(created.message(), checked.message());
  }
}

TEST(CalibrationQuantities, TheAxesOfAVectorShareTheirRange) {
  for (const char* axes : {"trunk_com_", "gyro_bias_", "accel_bias_"}) {
    const CalibrationQuantity* x = find_calibration_quantity(std::string(axes) + "x");
    ASSERT_NE(x, nullptr) << axes;
    EXPECT_EQ(x->min, -x->max);
    for (const char* axis : {"y", "z"})
      if (const CalibrationQuantity* q = find_calibration_quantity(std::string(axes) + axis)) {
        EXPECT_EQ(q->min, x->min) << q->name;
        EXPECT_EQ(q->max, x->max) << q->name;
      }
  }
}

}  // namespace
}  // namespace stride::sim
