// What every physics engine shares: engine names, the state hash and the state check.
#include "stride/sim_hal/physics_engine.hpp"

#include <cmath>

namespace stride::sim {

const char* to_string(EngineKind kind) {
  switch (kind) {
    case EngineKind::kSimbody:
      return "simbody";
    case EngineKind::kMujoco:
      return "mujoco";
  }
  return "unknown";
}

bool parse_engine_kind(std::string_view text, EngineKind& out) {
  if (text == "simbody") {
    out = EngineKind::kSimbody;
  } else if (text == "mujoco") {
    out = EngineKind::kMujoco;
  } else {
    return false;
  }
  return true;
}

bool parse_contact_kind(std::string_view text, ContactOptions& out) {
  if (text == "seed") {
    out = ContactOptions::seed();
  } else if (text == "turf") {
    out = ContactOptions::turf();
  } else if (text == "soft") {
    out = ContactOptions::soft();
  } else if (text == "hard") {
    out = ContactOptions::hard();
  } else {
    return false;
  }
  return true;
}

const char* contact_kind_name(const ContactOptions& c) {
  for (const char* name : {"turf", "seed", "soft", "hard"}) {
    ContactOptions g;
    parse_contact_kind(name, g);
    if (c.grass_thickness_m == g.grass_thickness_m &&
        c.grass_stiffness_n_m == g.grass_stiffness_n_m &&
        c.grass_damping_n_s_m == g.grass_damping_n_s_m &&
        c.ground_stiffness_n_m == g.ground_stiffness_n_m &&
        c.ground_damping_n_s_m == g.ground_damping_n_s_m &&
        c.tangential_stiffness_n_m == g.tangential_stiffness_n_m &&
        c.tangential_damping_n_s_m == g.tangential_damping_n_s_m &&
        c.mujoco_solid_ground == g.mujoco_solid_ground)
      return name;
  }
  return "custom";
}

const char* to_string(WorldPreset preset) {
  return preset == WorldPreset::kSeed ? "seed" : "faithful";
}

bool parse_world_preset(std::string_view text, WorldPreset& out) {
  if (text == "faithful") {
    out = WorldPreset::kFaithful;
  } else if (text == "seed") {
    out = WorldPreset::kSeed;
  } else {
    return false;
  }
  return true;
}

void WorldOptions::use_cm730_imu(bool cm730) {
  use_imu(cm730 ? ImuKind::kCm730 : ImuKind::kIdeal);
}

void WorldOptions::use_imu(ImuKind kind) {
  const bool noise = imu.chain.noise;
  imu.chain = kind == ImuKind::kIdeal         ? ImuChain::ideal()
              : kind == ImuKind::kCm730Nimbro ? ImuChain::cm730_nimbro()
                                              : ImuChain{};
  imu.chain.noise = noise;
}

ImuKind WorldOptions::imu_kind() const {
  if (imu.chain.is_ideal()) return ImuKind::kIdeal;
  return imu.chain.magnetometer.present ? ImuKind::kCm730Nimbro : ImuKind::kCm730;
}

const char* to_string(ImuKind kind) {
  switch (kind) {
    case ImuKind::kIdeal:
      return "ideal";
    case ImuKind::kCm730:
      return "cm730";
    case ImuKind::kCm730Nimbro:
      return "cm730-nimbro";
  }
  return "?";
}

void WorldOptions::apply(WorldPreset preset) {
  const bool thesis = preset == WorldPreset::kSeed;
  servo.law = thesis ? ServoLaw::kSeed : ServoLaw::kIdentified;
  use_cm730_imu(!thesis);
  contact = thesis ? ContactOptions::seed() : ContactOptions::turf();
}

std::uint64_t fnv1a(std::uint64_t hash, const void* data, std::size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) {
    hash ^= p[i];
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

WorldStatus check_state(const double* q, std::size_t nq, const double* u, std::size_t nu,
                        double max_speed, double time_s, std::string& reason) {
  for (std::size_t i = 0; i < nq; ++i)
    if (!std::isfinite(q[i])) {
      reason = "non-finite coordinate q[" + std::to_string(i) + "] at t=" + std::to_string(time_s) +
               " s";
      return WorldStatus::kNonFinite;
    }
  for (std::size_t i = 0; i < nu; ++i) {
    if (!std::isfinite(u[i])) {
      reason =
          "non-finite speed u[" + std::to_string(i) + "] at t=" + std::to_string(time_s) + " s";
      return WorldStatus::kNonFinite;
    }
    if (std::abs(u[i]) > max_speed) {
      reason = "exploding state: |u[" + std::to_string(i) +
               "]| = " + std::to_string(std::abs(u[i])) + " > " + std::to_string(max_speed) +
               " at t=" + std::to_string(time_s) + " s";
      return WorldStatus::kExploded;
    }
  }
  return WorldStatus::kRunning;
}

}  // namespace stride::sim
