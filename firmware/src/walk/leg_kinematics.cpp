// Forward and inverse kinematics of the igus leg (derivation in leg_kinematics.hpp).
#include "stride/firmware/walk/leg_kinematics.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace stride::fw::walk {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

Matrix3d rot_x(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Matrix3d m;
  m << 1, 0, 0, 0, c, -s, 0, s, c;
  return m;
}
Matrix3d rot_y(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Matrix3d m;
  m << c, 0, s, 0, 1, 0, -s, 0, c;
  return m;
}
Matrix3d rot_z(double a) {
  const double c = std::cos(a), s = std::sin(a);
  Matrix3d m;
  m << c, -s, 0, s, c, 0, 0, 0, 1;
  return m;
}

/// Angle of a vector in the sagittal (x, z) plane such that Ry(t) adds t to it.
double sagittal_angle(double x, double z) {
  return std::atan2(x, z);
}

/// Smooth one-sided clamp: identity below `knee`, then an exponential approach to
/// knee + band (value and slope continuous).
double soft_upper(double r, double limit, double band) {
  const double knee = limit - band;
  if (r <= knee) return r;
  return limit - band * std::exp(-(r - knee) / band);
}
double soft_lower(double r, double limit, double band) {
  const double knee = limit + band;
  if (r >= knee) return r;
  return limit + band * std::exp(-(knee - r) / band);
}

/// std::remainder(angle, 2 pi), skipping the division where the angle is already in
/// [-pi, pi]: there the remainder is the angle itself, exactly.
double wrap_angle(double angle) {
  if (std::abs(angle) <= std::numbers::pi) return angle;
  return std::remainder(angle, 2.0 * std::numbers::pi);
}

bool finite(const Pose3& p) {
  return p.rotation.allFinite() && p.position.allFinite();
}

}  // namespace

LegKinematics::LegKinematics(LegSide side) noexcept
    : side_(side),
      yaw_origin_(LegGeometry::kHipYawX, static_cast<int>(side) * LegGeometry::kHipYawY,
                  LegGeometry::kHipYawZ) {
  shank_length_ = std::hypot(LegGeometry::kShankX, LegGeometry::kShankZ);
  shank_angle_ = std::atan2(LegGeometry::kShankX, LegGeometry::kShankZ);
  const double l1 = LegGeometry::kThigh;
  reach_max_ = l1 + shank_length_;
  reach_min_ = std::sqrt(l1 * l1 + shank_length_ * shank_length_ +
                         2.0 * l1 * shank_length_ * std::cos(kKneeMax - shank_angle_));
}

Vector3d LegKinematics::hip_point(double hip_yaw) const noexcept {
  return yaw_origin_ +
         rot_z(hip_yaw) * Vector3d(LegGeometry::kYawToHipX, 0.0, LegGeometry::kYawToHipZ);
}

Pose3 LegKinematics::forward(const LegJoints& q) const noexcept {
  const Vector3d l1(0.0, 0.0, -LegGeometry::kThigh);
  const Vector3d l2(LegGeometry::kShankX, 0.0, -LegGeometry::kShankZ);
  const Matrix3d yaw = rot_z(q.hip_yaw);
  const Matrix3d roll = rot_x(q.hip_roll);
  Pose3 pose;
  pose.position = hip_point(q.hip_yaw) +
                  yaw * roll * (rot_y(q.hip_pitch) * l1 + rot_y(q.hip_pitch + q.knee) * l2);
  pose.rotation = yaw * roll * rot_y(q.hip_pitch + q.knee + q.ankle_pitch) * rot_x(q.ankle_roll);
  return pose;
}

LegIkResult LegKinematics::inverse(const Pose3& target) const noexcept {
  LegIkResult result;
  if (!finite(target)) {
    result.clamped = true;
    return result;
  }
  const Matrix3d& r_foot = target.rotation;
  const double l1 = LegGeometry::kThigh;
  const double l2 = shank_length_;
  // For a hip-yaw guess: the joints that reach the target from the hip crossing H(yaw), and
  // the yaw those joints imply. The solution is the fixed point yaw = implied(yaw).
  auto solve_for_yaw = [&](double yaw, LegJoints& q, bool& clamped) {
    Vector3d v = r_foot.transpose() * (hip_point(yaw) - target.position);
    double distance = v.norm();
    if (!(distance > 1e-9)) {
      v = Vector3d(0.0, 0.0, 1.0);
      distance = 0.0;
    }
    const double ankle_roll = std::atan2(v.y(), v.z());
    const Matrix3d roll = rot_x(ankle_roll);
    const Matrix3d unroll = roll.transpose();  // rot_x(-ankle_roll), without another sin/cos
    const Vector3d w = roll * v;               // w.y() == 0
    double reach = soft_upper(distance, reach_max_, kSoftBand);
    reach = soft_lower(reach, reach_min_, kSoftBand);
    clamped = distance > reach_max_ - kSoftBand || distance < reach_min_ + kSoftBand;
    // Knee from |Ry(-knee) l1 + l2| = reach.
    const double cos_term =
        std::clamp((reach * reach - l1 * l1 - l2 * l2) / (2.0 * l1 * l2), -1.0, 1.0);
    const double knee = shank_angle_ + std::acos(cos_term);
    // u = Ry(-knee) l1 + l2 and -w = Ry(-ankle_pitch) u.
    const double ux = l1 * std::sin(knee) + LegGeometry::kShankX;
    const double uz = -l1 * std::cos(knee) - LegGeometry::kShankZ;
    const double ankle_pitch = sagittal_angle(ux, uz) - sagittal_angle(-w.x(), -w.z());
    // Rz(yaw) Rx(roll) Ry(pitch) = R_foot Rx(-ankle_roll) Ry(-knee - ankle_pitch).
    const Matrix3d m = r_foot * unroll * rot_y(-knee - ankle_pitch);
    q.hip_yaw = std::atan2(-m(0, 1), m(1, 1));
    q.hip_roll = std::atan2(m(2, 1), std::hypot(m(0, 1), m(1, 1)));
    q.hip_pitch = std::atan2(-m(2, 0), m(2, 2));
    q.knee = knee;
    q.ankle_pitch = wrap_angle(ankle_pitch);
    q.ankle_roll = ankle_roll;
    return wrap_angle(q.hip_yaw - yaw);  // residual
  };
  // Secant iteration on the residual (fixed-point steps where the secant is ill-conditioned).
  LegJoints q;
  bool clamped = false;
  double yaw_a = 0.0;  // the hip moves by only 23 mm per rad of yaw: 0 is a safe start
  double res_a = solve_for_yaw(yaw_a, q, clamped);
  double yaw_b = yaw_a + res_a;
  for (int iteration = 0; iteration < 60 && std::abs(res_a) > 1e-14; ++iteration) {
    const double res_b = solve_for_yaw(yaw_b, q, clamped);
    if (std::abs(res_b) <= 1e-14) break;
    const double slope = (res_b - res_a) / (yaw_b - yaw_a);
    // Secant step, limited to 0.1 rad so the iteration stays on the branch of the initial
    // guess (yaw + pi with flipped roll and ankle roll is another exact solution).
    double step = res_b;
    if (std::isfinite(slope) && std::abs(slope) > 1e-6) step = -res_b / slope;
    const double next = yaw_b + std::clamp(step, -0.1, 0.1);
    yaw_a = yaw_b;
    res_a = res_b;
    yaw_b = next;
  }
  result.clamped = clamped;
  result.joints = q;
  return result;
}

}  // namespace stride::fw::walk
