// An episode's randomised values written into a compiled MuJoCo model (see episode_values.hpp;
// the compiler's rules quoted are MuJoCo 2.2.2's src/user/user_model.cc and user_objects.cc).
#include "episode_values.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace stride::sim::mujoco {
namespace {

/// The nominal values of the fields written per episode.
constexpr double kNominalFriction = 1.0;
/// The compiler's threshold on the smallest principal moment (user_util.h: mjEPS).
constexpr double kCompilerEps = 1e-14;

/// The compiler's mjCModel::IsNullPose: position zero and quaternion (1, 0, 0, 0), exactly.
bool null_pose(const mjtNum* pos, const mjtNum* quat) {
  return pos[0] == 0 && pos[1] == 0 && pos[2] == 0 && quat[0] == 1 && quat[1] == 0 &&
         quat[2] == 0 && quat[3] == 0;
}

/// The compiler's geom_sameframe of geom `g` at position `pos` in a body whose inertial frame
/// is (ipos, iquat): 1 the body frame, 2 the inertial frame, 0 neither.
int geom_sameframe(const mjModel* m, int g, const mjtNum* pos, const mjtNum* ipos,
                   const mjtNum* iquat) {
  const mjtNum* quat = m->geom_quat + 4 * g;
  if (null_pose(pos, quat)) return 1;
  return std::equal(pos, pos + 3, ipos) && std::equal(quat, quat + 4, iquat) ? 2 : 0;
}

/// One robot body's inertial values for the episode.
struct Inertial {
  int body = -1;
  mjtNum mass = 0, ipos[3] = {}, iquat[4] = {}, inertia[3] = {};
};

/// The compiler's inertial of link `l` under `model` (mass, principal moments and axes of
/// <inertial fullinertia>, centre of mass), or false where the compiler would refuse it or
/// set another sameframe flag than `m`'s.
bool inertial_of(const mjModel* m, const EngineModel& model, std::size_t l, Inertial& out) {
  const LinkSpec& link = model.robot->links()[l];
  out.body = mj_name2id(m, mjOBJ_BODY, ("l" + std::to_string(l)).c_str());
  if (out.body < 0) return false;
  const double s = model.link_mass_scale[l];
  const Eigen::Matrix3d& i = link.inertia;
  // The numbers write_mjcf prints (ixx iyy izz ixy ixz iyz), as the compiler arranges them.
  const double xx = s * i(0, 0), yy = s * i(1, 1), zz = s * i(2, 2), xy = s * i(0, 1),
               xz = s * i(0, 2), yz = s * i(1, 2);
  const mjtNum full[9] = {xx, xy, xz, xy, yy, yz, xz, yz, zz};
  if (!std::all_of(full, full + 9, [](double v) { return std::isfinite(v); })) return false;
  mjtNum axes[9];
  mju_eig3(out.inertia, axes, out.iquat, full);
  out.mass = s * link.mass;
  const Eigen::Vector3d com = l == 0 ? Eigen::Vector3d(link.com + model.root_com_shift) : link.com;
  for (int k = 0; k < 3; ++k) out.ipos[k] = com[k];
  // The compiler's checks (boundmass and boundinertia are 0): positive eigenvalues, A + B >= C,
  // a moving body's mass and moments at least mjMINVAL.
  const mjtNum* p = out.inertia;
  if (!std::isfinite(out.mass) || !(out.mass >= mjMINVAL) || !(p[2] >= kCompilerEps) ||
      !(p[0] >= mjMINVAL && p[1] >= mjMINVAL) || !std::isfinite(p[0]) || p[0] + p[1] < p[2] ||
      p[0] + p[2] < p[1] || p[1] + p[2] < p[0] ||
      !std::all_of(out.ipos, out.ipos + 3, [](double v) { return std::isfinite(v); }))
    return false;
  // The flags the compiler derives from the inertial frame stay the nominal model's.
  if (null_pose(out.ipos, out.iquat) != (m->body_sameframe[out.body] != 0)) return false;
  for (int g = m->body_geomadr[out.body];
       g >= 0 && g < m->body_geomadr[out.body] + m->body_geomnum[out.body]; ++g)
    if (geom_sameframe(m, g, m->geom_pos + 3 * g, out.ipos, out.iquat) != m->geom_sameframe[g])
      return false;
  return true;
}

}  // namespace

EngineModel nominal_model(const EngineModel& model) {
  EngineModel n = model;
  std::fill(n.link_mass_scale.begin(), n.link_mass_scale.end(), 1.0);
  n.root_com_shift.setZero();
  n.friction = kNominalFriction;
  n.contact.grass_thickness_m = ContactOptions::seed().grass_thickness_m;
  return n;
}

bool write_episode_values(mjModel* m, mjData* d, const EngineModel& model) {
  const std::size_t links = model.robot->links().size();
  if (model.link_mass_scale.size() != links) return false;
  std::vector<Inertial> inertials(links);
  for (std::size_t l = 0; l < links; ++l)
    if (!inertial_of(m, model, l, inertials[l])) return false;
  const double mu = model.friction, top = model.contact.grass_thickness_m;
  if (!(std::isfinite(mu) && mu >= 0.0) || !std::isfinite(top)) return false;
  const int grass = mj_name2id(m, mjOBJ_GEOM, "grass");
  const int ground = mj_name2id(m, mjOBJ_GEOM, "ground");  // -1 unless mujoco_solid_ground
  if (grass < 0 || m->geom_bodyid[grass] != 0) return false;
  const mjtNum grass_pos[3] = {0.0, 0.0, top};
  if (geom_sameframe(m, grass, grass_pos, m->body_ipos, m->body_iquat) != m->geom_sameframe[grass])
    return false;

  for (const Inertial& in : inertials) {
    m->body_mass[in.body] = in.mass;
    std::copy(in.ipos, in.ipos + 3, m->body_ipos + 3 * in.body);
    std::copy(in.iquat, in.iquat + 4, m->body_iquat + 4 * in.body);
    std::copy(in.inertia, in.inertia + 3, m->body_inertia + 3 * in.body);
  }
  // Robot, ball and grass geoms carry "mu 0.005 0.0001", the ground pairs
  // "mu mu 0.005 0.0001 0.0001"; the ball-robot pairs (frictionless, condim 1) have no friction
  // in the text and keep MuJoCo's default pair friction (1 1 ...).
  for (int g = 0; g < m->ngeom; ++g)
    if (g != ground) m->geom_friction[3 * g] = mu;
  for (int p = 0; p < m->npair; ++p)
    if (ground >= 0 && m->pair_geom1[p] == ground)
      m->pair_friction[5 * p] = m->pair_friction[5 * p + 1] = mu;
  std::copy(grass_pos, grass_pos + 3, m->geom_pos + 3 * grass);
  mj_setConst(m, d);
  return true;
}

}  // namespace stride::sim::mujoco
