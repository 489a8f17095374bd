// Soft-contact parameters of the MuJoCo engine (derivation in contact_params.hpp).
#include "contact_params.hpp"

#include <algorithm>
#include <cmath>

#include "mjcf_model.hpp"

namespace stride::sim::mujoco {
namespace {

/// Standard-format solref (time constant, damping ratio) giving `stiffness` [N/m] of static
/// stiffness per contact whose two bodies' translational inverse weights sum to `inv_weight`.
void set(mjtNum* solref, mjtNum* solimp, double stiffness, double inv_weight,
         double damping_ratio = kDampingRatio) {
  const double d = kContactImpedance;
  solref[0] = 1.0 / (damping_ratio * std::sqrt(stiffness * (1.0 - d) * inv_weight));
  solref[1] = damping_ratio;
  solimp[0] = d;  // flat impedance: d at any depth
  solimp[1] = d;
  solimp[2] = 0.001;
  solimp[3] = 0.5;
  solimp[4] = 2.0;
}

double tran_weight(const mjModel* m, int geom) {
  return m->body_invweight0[2 * m->geom_bodyid[geom]];
}

}  // namespace

double field_damping_ratio(const ContactOptions& c) {
  const ContactOptions grass = ContactOptions::seed();
  const double relative = (c.grass_damping_n_s_m / std::sqrt(c.grass_stiffness_n_m)) /
                          (grass.grass_damping_n_s_m / std::sqrt(grass.grass_stiffness_n_m));
  return kDampingRatio * std::max(1.0, relative);
}

void set_contact_params(mjModel* m, const EngineModel& model) {
  const ContactOptions& c = model.contact;
  const int field = mj_name2id(m, mjOBJ_GEOM, "grass");
  const double damping_ratio = field_damping_ratio(c);
  for (int g = 0; g < m->ngeom; ++g) {
    if (g == field) continue;
    set(m->geom_solref + mjNREF * g, m->geom_solimp + mjNIMP * g, c.grass_stiffness_n_m,
        tran_weight(m, g), damping_ratio);
  }
  const int ground = mj_name2id(m, mjOBJ_GEOM, "ground");  // -1 unless mujoco_solid_ground
  for (int p = 0; p < m->npair; ++p)
    set(m->pair_solref + mjNREF * p, m->pair_solimp + mjNIMP * p,
        m->pair_geom1[p] == ground ? c.ground_stiffness_n_m : c.ball_robot_stiffness_n_m,
        tran_weight(m, m->pair_geom1[p]) + tran_weight(m, m->pair_geom2[p]));
}

}  // namespace stride::sim::mujoco
