// Placing the robot at a reset (SimWorld::reset, ResetSpec): the trunk's attitude, its height
// on the grass and the speeds it starts with, read from the engine's own kinematics. Private to
// sim_hal's sources.
#pragma once

#include <vector>

#include "stride/core/status.hpp"
#include "stride/sim_hal/collision_points.hpp"
#include "stride/sim_hal/physics_engine.hpp"
#include "stride/sim_hal/sim_world.hpp"

namespace stride::sim {

/// Places the robot for a reset on `engine`: the given orientation, tilted so that the mean
/// sole normal points up if asked, lowered until the lowest collision point rests on the grass
/// top (or sunk to carry `weight_n`, ResetSpec::sink_into_grass) unless a height is given.
Status place_robot(PhysicsEngine& engine, const std::vector<CollisionPoint>& points,
                   const ResetSpec& spec, int left_foot, int right_foot,
                   const ContactOptions& contact, double weight_n, EngineStart& start);

/// Gives the trunk of a robot placed by `start` (with joint speeds) the velocity that keeps its
/// lower foot still (ResetSpec::still_lower_foot).
Status still_lower_foot(PhysicsEngine& engine, int left_foot, int right_foot, EngineStart& start);

}  // namespace stride::sim
