// Conversions between Eigen (Stride's interfaces) and SimTK (the Simbody engine's inside).
#pragma once

#include <Simbody.h>
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace stride::sim::simbody {

inline SimTK::Vec3 to_vec3(const Eigen::Vector3d& v) {
  return {v.x(), v.y(), v.z()};
}
inline Eigen::Vector3d to_eigen(const SimTK::Vec3& v) {
  return {v[0], v[1], v[2]};
}
inline SimTK::Rotation to_rotation(const Eigen::Matrix3d& m) {
  SimTK::Mat33 mat;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) mat(r, c) = m(r, c);
  return SimTK::Rotation(mat, true);
}
inline SimTK::Transform to_transform(const Eigen::Isometry3d& x) {
  return {to_rotation(x.linear()), to_vec3(x.translation())};
}
inline Eigen::Isometry3d to_isometry(const SimTK::Transform& x) {
  Eigen::Isometry3d out = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out.linear()(r, c) = x.R().asMat33()(r, c);
  out.translation() = to_eigen(x.p());
  return out;
}

}  // namespace stride::sim::simbody
