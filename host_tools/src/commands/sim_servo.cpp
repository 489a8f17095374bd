// `stride sim servo`: one simulated MX servo on a bench like Rhoban BAM's (no-load speed,
// blocked duty and torque, pendulum trace), to compare the servo model with measured tables.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

#include "stride/core/cli_args.hpp"
#include "stride/host_tools/command_errors.hpp"
#include "stride/sim_hal/servo_bench.hpp"

namespace {

using stride::Status;
namespace sim = stride::sim;

const stride::tools::CommandErrors errors("sim servo");

void declare_options(stride::core::CliArgs& args) {
  args.option("help", "show this help", false);
  args.option("model", "servo: mx64 or mx106", true, "mx106");
  args.option("experiment", "no-load, blocked or pendulum", true, "no-load");
  args.option("friction", "identified friction model: m6 (default) or m1", true, "m6");
  args.option("voltage", "supply voltage [V], 1-24", true, "15");
  args.option("p-gain", "P register, 0-254", true, "32");
  args.option("error-deg", "blocked: goal minus position [deg]", true, "10");
  args.option("arm-length", "pendulum: arm length [m]", true, "0.15");
  args.option("arm-mass", "pendulum: point mass at the arm's end [kg]", true, "0.5");
  args.option("trajectory", "pendulum: sin-time-square, lift-and-drop, up-and-down or sin-sin",
              true, "sin-time-square");
  args.option("duration", "no-load and pendulum: run length [s]", true, "6");
  args.option("json", "print the result as one JSON object", false);
}

void print_help(const stride::core::CliArgs& args) {
  std::printf(
      "usage: stride sim servo --model mx64|mx106 --experiment no-load|blocked|pendulum "
      "[options]\n\n"
      "no-load: output free, goal far away; prints the steady speed (speed_rad_s).\n"
      "blocked: output held still, goal --error-deg away; prints duty and torque_nm.\n"
      "pendulum: a point mass on an arm swinging under gravity on a BAM trajectory;\n"
      "          --json prints the trace (t, goal, position, speed, torque).\n\n%s",
      args.help().c_str());
}

}  // namespace

/// argv starts at "servo".
int run_sim_servo(int argc, char** argv) {
  stride::core::CliArgs args;
  declare_options(args);
  if (Status s = args.parse(argc, argv); !s) return errors.bad_input(s.message());
  if (args.has("help")) {
    print_help(args);
    return 0;
  }
  if (!args.positional().empty())
    return errors.bad_input("unexpected argument '" + args.positional()[0] + "'");
  sim::ServoBenchOptions o;
  for (Status s :
       {sim::parse_servo_model(args.get("model"), o.model),
        sim::parse_bench_experiment(args.get("experiment"), o.experiment),
        sim::parse_friction_model(args.get("friction"), o.friction),
        sim::parse_bench_trajectory(args.get("trajectory"), o.trajectory),
        args.get_double("voltage", o.voltage_v), args.get_double("p-gain", o.p_gain),
        args.get_double("error-deg", o.error_deg), args.get_double("arm-length", o.arm_length_m),
        args.get_double("arm-mass", o.arm_mass_kg), args.get_double("duration", o.duration_s),
        sim::validate(o)})
    if (!s) return errors.bad_input(s.message());
  if (o.experiment == sim::BenchExperiment::kNoLoad && !args.has("duration")) o.duration_s = 2.0;

  const sim::ServoBenchResult r = sim::run_servo_bench(o);
  const std::string model = args.get("model"), experiment = args.get("experiment");
  if (args.has("json")) {
    nlohmann::json out = {{"model", model},
                          {"experiment", experiment},
                          {"voltage_v", o.voltage_v},
                          {"friction", args.get("friction")}};
    if (o.experiment == sim::BenchExperiment::kNoLoad) {
      out["speed_rad_s"] = r.speed_rad_s;
    } else if (o.experiment == sim::BenchExperiment::kBlocked) {
      out["p_gain"] = o.p_gain;
      out["error_deg"] = o.error_deg;
      out["duty"] = r.duty;
      out["torque_nm"] = r.torque_nm;
    } else {
      out["trajectory"] = args.get("trajectory");
      out["p_gain"] = o.p_gain;
      out["arm_length_m"] = o.arm_length_m;
      out["arm_mass_kg"] = o.arm_mass_kg;
      nlohmann::json trace = nlohmann::json::array();
      for (const sim::BenchSample& s : r.trace)
        trace.push_back({{"t", s.t},
                         {"goal", s.goal},
                         {"position", s.position},
                         {"speed", s.speed},
                         {"torque", s.torque}});
      out["trace"] = std::move(trace);
    }
    std::printf("%s\n", out.dump().c_str());
    return 0;
  }
  if (o.experiment == sim::BenchExperiment::kNoLoad) {
    std::printf("%s no-load at %.2f V: speed %.3f rad/s\n", model.c_str(), o.voltage_v,
                r.speed_rad_s);
  } else if (o.experiment == sim::BenchExperiment::kBlocked) {
    std::printf("%s blocked at %.2f V, P %.0f, error %.2f deg: duty %.4f, torque %.3f N m\n",
                model.c_str(), o.voltage_v, o.p_gain, o.error_deg, r.duty, r.torque_nm);
  } else {
    double max_error = 0.0;
    for (const sim::BenchSample& s : r.trace)
      max_error = std::max(max_error, std::abs(s.goal - s.position));
    std::printf(
        "%s pendulum (%s, %.3f m, %.3f kg, P %.0f) for %.1f s: final position %.4f rad, "
        "largest |goal - position| %.4f rad (--json for the trace)\n",
        model.c_str(), args.get("trajectory").c_str(), o.arm_length_m, o.arm_mass_kg, o.p_gain,
        o.duration_s, r.trace.empty() ? 0.0 : r.trace.back().position, max_error);
  }
  return 0;
}
