// The 3D replay of the report pages (replay3d.js draws it with three.js): the robot's links as
// the URDF's collision boxes and spheres, posed by the recorded torso pose and joint angles
// (forward kinematics in the page), the feet's contact forces as arrows, the ground, the goal
// line and the ball.
//
// three.js is Debian's libjs-three (r111), read at report time from
// /usr/share/javascript/three/three.min.js ($STRIDE_THREE_JS overrides the path) and inlined,
// so the page stays one file that works from file:// without a network. Without it, or with a
// robot model the page cannot draw, the page says what is missing and the caller gets one
// warning; the 2D replay is unaffected.
//
// Motion data per individual: base64 of little-endian int16 per frame (the EpisodeCapture's
// frames, 25 per second): torso position [mm] (3), torso quaternion w,x,y,z [1e-4] (4), the
// model's joint angles [1e-4 rad] (one per joint), left and right foot contact force [N] (3 + 3),
// ball [mm] (3). 20 joints: 72 bytes per frame, about 2.4 kB per second of episode.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "stride/optimiser/report/html_page.hpp"
#include "stride/optimiser/report/html_replay.hpp"

namespace stride::opt::report {

/// Where three.min.js is read from: $STRIDE_THREE_JS, else Debian's libjs-three path.
std::string three_js_path();

/// three.min.js, or "" and `problem` saying why the 3D view is unavailable.
std::string load_three_js(std::string& problem);

/// The robot description replay3d.js poses: links (boxes [x,y,z, qw,qx,qy,qz, sx,sy,sz],
/// spheres [x,y,z,r,stud]), joints (parent, child, origin [x,y,z, qw,qx,qy,qz], axis), the
/// feet's link indices and the values per motion frame. null and `problem` set when the model
/// has nothing to draw.
nlohmann::json robot3d_model(const sim::RobotModel& model, std::string& problem);

/// One individual's motion data (see above); "" and `problem` set when its capture cannot be
/// posed on `model` (no frames, joint angles missing or of another count).
std::string robot3d_motion(const sim::RobotModel& model, const ReplayIndividual& individual,
                           std::string& problem);

/// The replay section of both pages: the 3D view (or a note saying why it is unavailable), the
/// shared controls and the 2D cards. Sets the page's replay data and scripts; appends at most
/// one warning (what the 3D view is missing) to `warnings`.
void add_replay_section(HtmlPage& page, const std::string& note, const sim::RobotModel& model,
                        const std::vector<ReplayIndividual>& individuals, const ReplayScene& scene,
                        std::vector<std::string>& warnings);

}  // namespace stride::opt::report
