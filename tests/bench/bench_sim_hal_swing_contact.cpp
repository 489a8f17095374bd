// How the grass slows a swing foot, per engine (issue 29 point 1): the firmware walks (any
// command, any world options), and at every control tick the foot carrying less than 15 % of
// the robot's weight is the swing foot. Reported over the swing samples after 5 s: the share
// in which the swing foot touches the grass, the mean horizontal and vertical contact force on
// it while it does, their ratio (Coulomb caps it at mu), the horizontal impulse per swing, and
// the median over swings of the lowest stud tip's clearance above the grass top (negative: in
// the grass); the walk's progress along the command (m/s or rad/s from 5 s, median of the
// seeds), how fast the feet carrying over half the weight slide along it (at their studs), and
// the feet's mean move along it split by load (lifted, partly loaded, loaded): stepping shows
// as the lifted part, sliding as the loaded part.
// The contact options below override ContactOptions fields for experiments.
// Run: build/release/bench/bench_sim_hal_swing_contact --params FILE --servo-law identified
//        --imu cm730 --engine simbody|mujoco --vy 1 [--seeds 3] [--duration 20]
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <memory>
#include <vector>

#include "stride/core/cli_args.hpp"
#include "stride/firmware/firmware.hpp"
#include "stride/sim_hal/collision_points.hpp"
#include "stride/sim_hal/episode.hpp"
#include "stride/sim_hal/sim_cli.hpp"
#include "stride/sim_hal/sim_robot.hpp"

namespace {

namespace fw = stride::fw;
namespace core = stride::core;
namespace hal = stride::hal;
namespace sim = stride::sim;

struct Totals {
  double swing_s = 0.0, touching_s = 0.0;
  double horizontal_n_s = 0.0, vertical_n_s = 0.0;
  int swings = 0;
  std::vector<double> lowest_clearance_mm;
  std::vector<double> impulse_per_swing;
  int falls = 0, runs = 0;
  double stance_slip_m = 0.0;  ///< stance feet's moves along the command, summed
  double stance_s = 0.0;
  /// Both feet's sole moves along the command while each carried under 15 %, 15-50 % and over
  /// 50 % of the weight, summed, and the time they were summed over.
  double move_m[3] = {0.0, 0.0, 0.0};
  double move_s = 0.0;
  std::vector<double> progress;  ///< per run: torso displacement 5 s .. end along the command
};

void walk(const sim::WorldOptions& options, const fw::FirmwareOptions& fw_options, double vx,
          double vy, double vth, double duration, Totals& totals) {
  std::unique_ptr<fw::Firmware> firmware;
  if (const stride::Status s = fw::Firmware::create(fw_options, firmware); !s) {
    std::fprintf(stderr, "%s\n", s.message().c_str());
    std::exit(2);
  }
  sim::WorldOptions o = options;
  o.control_period_ns = firmware->period_ns();
  std::unique_ptr<sim::SimWorld> world;
  if (const stride::Status s = sim::SimWorld::create(o, world); !s) {
    std::fprintf(stderr, "%s\n", s.message().c_str());
    std::exit(2);
  }
  sim::SimRobot robot(std::move(world));
  const sim::RobotModel& model = robot.world().model();
  const int feet[2] = {model.link_index("left_foot_link"), model.link_index("right_foot_link")};
  std::vector<sim::CollisionPoint> studs[2];
  for (const sim::CollisionPoint& p : sim::collision_points(model))
    for (int f = 0; f < 2; ++f)
      if (p.link == feet[f] && p.radius > 0.0) studs[f].push_back(p);
  double mass = 0.0;
  for (const sim::LinkSpec& l : model.links()) mass += l.mass;
  const double weight = mass * o.gravity_mps2, grass = o.contact.grass_thickness_m;
  const double dt = static_cast<double>(o.control_period_ns) * 1e-9;
  int swing_foot = -1;  // the foot of the swing in progress
  double lowest = 0.0, impulse = 0.0;
  Eigen::Vector3d stance_last[2] = {Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  bool stance_was[2] = {false, false};
  bool have_last_sole = false;
  Eigen::Vector3d last_sole[2];
  const Eigen::Vector3d along =
      vy != 0 ? Eigen::Vector3d(0, vy > 0 ? 1 : -1, 0) : Eigen::Vector3d(vx >= 0 ? 1 : -1, 0, 0);
  auto close_swing = [&] {
    if (swing_foot < 0) return;
    ++totals.swings;
    totals.lowest_clearance_mm.push_back(1e3 * lowest);
    totals.impulse_per_swing.push_back(impulse);
    swing_foot = -1;
  };
  // The mean of a foot's stud centres: where the sole meets the grass (a foot that rolls moves
  // its ankle, not its studs).
  auto sole = [&studs](int f, const Eigen::Isometry3d& x) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const sim::CollisionPoint& p : studs[f]) sum += x * p.station;
    return Eigen::Vector3d(sum / static_cast<double>(std::max<std::size_t>(1, studs[f].size())));
  };
  fw::Controller& controller = firmware->controller();
  controller.request(fw::MotionRequest::walk(vx, vy, vth));
  sim::EpisodeOptions episode;
  episode.duration_s = duration;
  episode.on_tick = [&](hal::Tick, const sim::SimWorld& w, const hal::SensorFrame&) {
    const sim::GroundTruth g = w.ground_truth();
    if (g.time_s < 5.0) return;
    const sim::FootContact* contact[2] = {&g.left_contact, &g.right_contact};
    const Eigen::Isometry3d* pose[2] = {&g.left_foot, &g.right_foot};
    int swing = -1;
    for (int f = 0; f < 2; ++f)
      if (contact[f]->force.z() < 0.15 * weight && contact[1 - f]->force.z() > 0.5 * weight)
        swing = f;
    for (int f = 0; f < 2; ++f) {  // each foot's move, by its load
      const Eigen::Vector3d p = sole(f, *pose[f]);
      if (have_last_sole) {
        const double load = contact[f]->force.z() / weight;
        totals.move_m[load < 0.15 ? 0 : load < 0.5 ? 1 : 2] += along.dot(p - last_sole[f]);
      }
      last_sole[f] = p;
    }
    if (have_last_sole) totals.move_s += dt;
    have_last_sole = true;
    for (int f = 0; f < 2; ++f) {  // a foot carrying over half the weight: does it slip?
      const bool stance = contact[f]->force.z() > 0.5 * weight;
      if (stance && stance_was[f]) {
        totals.stance_slip_m += along.dot(sole(f, *pose[f]) - stance_last[f]);
        totals.stance_s += dt;
      }
      stance_was[f] = stance;
      stance_last[f] = sole(f, *pose[f]);
    }
    if (swing != swing_foot) close_swing();
    if (swing < 0) return;
    if (swing_foot < 0) {
      swing_foot = swing;
      lowest = std::numeric_limits<double>::infinity();
      impulse = 0.0;
    }
    for (const sim::CollisionPoint& p : studs[swing])
      lowest = std::min(lowest, (*pose[swing] * p.station).z() - p.radius - grass);
    totals.swing_s += dt;
    if (contact[swing]->points_in_contact > 0) {
      totals.touching_s += dt;
      const double fh = contact[swing]->force.head<2>().norm();
      totals.horizontal_n_s += fh * dt;
      totals.vertical_n_s += contact[swing]->force.z() * dt;
      impulse += fh * dt;
    }
  };
  Eigen::Vector3d start_p = Eigen::Vector3d::Zero();
  double start_yaw = 0.0, end_time = 0.0, yaw = 0.0, last_yaw = 0.0;
  auto old_tick = episode.on_tick;
  episode.on_tick = [&](hal::Tick tick, const sim::SimWorld& w, const hal::SensorFrame& s) {
    const Eigen::Isometry3d torso = w.torso_pose();
    const double y = std::atan2(torso.linear()(1, 0), torso.linear()(0, 0));
    yaw += std::remainder(y - last_yaw, 2 * M_PI);
    last_yaw = y;
    if (tick == 500) {
      start_p = torso.translation();
      start_yaw = yaw;
    }
    if (tick > 500) {
      const Eigen::Vector3d d = torso.translation() - start_p;
      end_time = w.time_s();
      const double moved = vth != 0 ? (yaw - start_yaw) : vy != 0 ? d.y() : d.x();
      if (totals.progress.size() < static_cast<std::size_t>(totals.runs + 1))
        totals.progress.push_back(0.0);
      totals.progress.back() = moved / (end_time - 5.0);
    }
    old_tick(tick, w, s);
  };
  const sim::EpisodeResult r = sim::run_episode(
      robot, [&](const hal::SensorFrame& s, hal::Tick t) { return controller.step(s, t); },
      episode);
  close_swing();
  ++totals.runs;
  if (r.fell) ++totals.falls;
}

double median(std::vector<double> v) {
  if (v.empty()) return std::nan("");
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  core::CliArgs args;
  args.option("params", "firmware parameter file (JSON)", true);
  args.option("vx", "walk command x", true, "0");
  args.option("vy", "walk command y", true, "0");
  args.option("vth", "walk command turn", true, "0");
  args.option("seeds", "seeds 1..N", true, "3");
  args.option("duration", "episode length [s]", true, "20");
  // Contact experiments (ContactOptions fields; default: the world's).
  args.option("grass-thickness", "grass layer [m]", true);
  args.option("grass-stiffness", "grass spring per point [N/m]", true);
  args.option("grass-damping", "grass damper per point [N s/m]", true);
  args.option("friction", "Coulomb coefficient", true);
  args.option("tangential-stiffness", "stick spring per point [N/m]", true);
  args.option("tangential-damping", "stick damper per point [N s/m]", true);
  sim::declare_world_options(args);
  sim::WorldOptions options;
  double vx = 0, vy = 0, vth = 0, duration = 20;
  std::int64_t seeds = 3;
  if (const stride::Status s = args.parse(argc, argv); !s) {
    std::fprintf(stderr, "%s\n", s.message().c_str());
    return 2;
  }
  if (!sim::read_world_options(args, options) || !args.get_double("vx", vx) ||
      !args.get_double("vy", vy) || !args.get_double("vth", vth) ||
      !args.get_double("duration", duration) || !args.get_int("seeds", seeds)) {
    std::fprintf(stderr, "bad option\n");
    return 2;
  }
  for (auto [name, field] : {std::pair{"grass-thickness", &options.contact.grass_thickness_m},
                             {"grass-stiffness", &options.contact.grass_stiffness_n_m},
                             {"grass-damping", &options.contact.grass_damping_n_s_m},
                             {"friction", &options.contact.friction},
                             {"tangential-stiffness", &options.contact.tangential_stiffness_n_m},
                             {"tangential-damping", &options.contact.tangential_damping_n_s_m}})
    if (args.has(name) && !args.get_double(name, *field)) return 2;
  fw::FirmwareOptions fw_options;
  if (args.has("params")) fw_options.params_file = args.get("params");
  Totals t;
  for (std::int64_t seed = 1; seed <= seeds; ++seed) {
    options.seed = static_cast<std::uint64_t>(seed);
    walk(options, fw_options, vx, vy, vth, duration, t);
  }
  const double touching = t.touching_s > 0 ? t.touching_s : 1.0;
  std::printf(
      "%s vx %.0f vy %.0f vth %.0f: progress %.3f (median, per s from 5 s); %d swings, falls %d; "
      "swing foot touching %.0f %% of swing time; while touching: horizontal %.2f N, vertical "
      "%.2f N, ratio %.2f; horizontal impulse per swing %.3f N s (median); lowest stud "
      "clearance per swing %.1f mm (median); stance feet slip along the command %.1f mm/s; "
      "the feet's mean move along it while under 15 %% / 15-50 %% / over 50 %% of the weight "
      "%.1f / %.1f / %.1f mm/s\n",
      sim::to_string(options.engine), vx, vy, vth, median(t.progress), t.swings, t.falls,
      100.0 * t.touching_s / std::max(t.swing_s, 1e-9), t.horizontal_n_s / touching,
      t.vertical_n_s / touching, t.horizontal_n_s / std::max(t.vertical_n_s, 1e-9),
      median(t.impulse_per_swing), median(t.lowest_clearance_mm),
      1e3 * t.stance_slip_m / std::max(t.stance_s, 1e-9),
      1e3 * t.move_m[0] / std::max(2 * t.move_s, 1e-9),
      1e3 * t.move_m[1] / std::max(2 * t.move_s, 1e-9),
      1e3 * t.move_m[2] / std::max(2 * t.move_s, 1e-9));
  return 0;
}
