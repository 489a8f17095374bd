// Report building blocks: 1-2-5 ticks, charts with the legend outside the plot and tooltips,
// the tolerant run-directory and validation.json readers, base64 and the stick figure, the
// replay's scene (the world's own ground and ball), the 3D replay's robot description and
// motion data and what its section says when a piece is missing.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "stride/optimiser/report/html_page.hpp"
#include "stride/optimiser/report/html_replay.hpp"
#include "stride/optimiser/report/html_replay3d.hpp"
#include "stride/optimiser/report/html_tables.hpp"
#include "stride/optimiser/report/run_data.hpp"
#include "stride/optimiser/report/run_plots.hpp"
#include "stride/optimiser/report/svg_chart.hpp"
#include "stride/sim_hal/stick_figure.hpp"
#include "temp_dir.hpp"

namespace stride::opt::report {
namespace {

TEST(ReportChart, TicksFallOnOneTwoFiveSteps) {
  // The old plot labelled 24.5, 25.08, 25.67...: now every step is 1, 2 or 5 x 10^k.
  for (auto [lo, hi] : {std::pair{24.5, 27.4},
                        {0.0, 1864.0},
                        {9.1, 22.3},
                        {0.001, 0.0173},
                        {-3.2, 2.9},
                        {5.0, 5.001}}) {
    const std::vector<double> t = nice_ticks(lo, hi);
    ASSERT_GE(t.size(), 2u) << lo << " " << hi;
    EXPECT_LE(t.front(), lo);
    EXPECT_GE(t.back(), hi - 1e-12);
    EXPECT_LE(t.size(), 13u);
    const double step = t[1] - t[0];
    const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
    EXPECT_TRUE(std::abs(mantissa - 1) < 1e-6 || std::abs(mantissa - 2) < 1e-6 ||
                std::abs(mantissa - 5) < 1e-6)
        << step;
    for (double v : t) EXPECT_NEAR(std::remainder(v, step), 0.0, step * 1e-6) << v;
  }
  const std::vector<double> t = nice_ticks(24.5, 27.4);
  EXPECT_EQ(t.front(), 24.5);
  EXPECT_EQ(t[1], 25.0);
  EXPECT_EQ(tick_label(25.0, 0.5), "25.0");
  EXPECT_EQ(tick_label(1800, 200), "1800");
  EXPECT_EQ(tick_label(0.015, 0.005), "0.015");
}

TEST(ReportChart, LegendSitsRightOfThePlotAreaAndPointsCarryTooltips) {
  ChartSpec spec;
  spec.title = "t";
  ChartSeries s;
  s.label = "generation 1";
  s.marker_r = 3;
  s.points = {{1, 5, "a & b"}, {2, 3, "c"}};
  spec.series.push_back(s);
  spec.markers.push_back({1.5, 4, "Ind_O", "#000", 's', "start"});
  const std::string svg = render_chart(spec);
  // The plot area's frame and every legend text.
  const std::string frame = "<rect x=\"74\" y=\"40\" width=\"";
  const std::size_t at_frame = svg.find(frame);
  ASSERT_NE(at_frame, std::string::npos);
  const double plot_right = 74 + std::stod(svg.substr(at_frame + frame.size()));
  int legend_items = 0;
  for (const char* label : {">generation 1<", ">Ind_O<"}) {  // the legend comes last
    const std::size_t at = svg.rfind(label);
    ASSERT_NE(at, std::string::npos) << label;
    const std::size_t x = svg.rfind("<text x=\"", at);
    EXPECT_GT(std::stod(svg.substr(x + 9)), plot_right) << label;
    ++legend_items;
  }
  EXPECT_EQ(legend_items, 2);
  EXPECT_NE(svg.find("<title>a &amp; b</title>"), std::string::npos);
  EXPECT_NE(svg.find("<title>start</title>"), std::string::npos);
}

TEST(ReportChart, ShownGenerationsRunFromFirstToLast) {
  EXPECT_EQ(shown_generations(50), (std::vector<int>{1, 9, 17, 25, 33, 41, 50}));
  EXPECT_EQ(shown_generations(2), (std::vector<int>{1, 2}));
  EXPECT_EQ(shown_generations(1), (std::vector<int>{1}));
  EXPECT_TRUE(shown_generations(0).empty());
}

TEST(ReportSettings, TheTableListsOnlyTheRunsOwnTasksSettings) {
  // An older walk run.json holds every task's fields; the table shows the walk's only.
  RunData data;
  data.task = "walk";
  data.run["task"] = {{"duration_s", 40.0},         {"goal_distance_m", 2.5}, {"walk_vx", 1.0},
                      {"script", "kick_right"},     {"kick_at_s", 1.0},       {"trials", 1},
                      {"yaw_drift_limit_rad", 6.66}};
  std::string html = settings_table_html(data);
  for (const char* shown : {"duration_s", "goal_distance_m", "walk_vx", "trials"})
    EXPECT_NE(html.find(shown), std::string::npos) << shown;
  for (const char* hidden : {"script", "kick_at_s", "yaw_drift_limit_rad"})
    EXPECT_EQ(html.find(hidden), std::string::npos) << hidden;
  data.task = "kick";
  html = settings_table_html(data);
  EXPECT_NE(html.find("kick_at_s"), std::string::npos);
  EXPECT_EQ(html.find("goal_distance_m"), std::string::npos);
}

TEST(ReportRunData, DamagedAndMissingPiecesBecomeWarnings) {
  test::TempDir tmp;
  tmp.write("run.json", R"({"problem":"walk","start":{"reals":[0.5]}})");
  tmp.write("evaluations.jsonl",
            R"({"id":0,"generation":1,"reals":[0.5],"objectives":[4.0,1.25],"violation":0})"
            "\n"
            R"({"id":1,"generation":1,"reals":[0.7],"objec)");  // torn last line
  tmp.write("pareto.csv", "f1,f2,g1\n4.0,1.25,0.5\n");
  RunData data;
  ASSERT_TRUE(load_run_data(tmp.path(), data).is_ok());
  EXPECT_EQ(data.evaluations.size(), 1u);
  EXPECT_EQ(data.front.size(), 1u);
  ASSERT_EQ(data.warnings.size(), 3u);
  EXPECT_NE(data.warnings[0].find("evaluations.jsonl: 1 damaged line(s) skipped, the first is "
                                  "line 2"),
            std::string::npos)
      << data.warnings[0];
  EXPECT_EQ(data.warnings[1], "generations.jsonl is missing");
  EXPECT_EQ(data.warnings[2], "front/000.json is missing (pareto.csv row 0)");
  ASSERT_NE(find_ind_o(data), nullptr);
  const auto picks = run_picks(data);
  ASSERT_EQ(picks.size(), 1u);  // one member is the fastest, the most stable and the knee
  EXPECT_EQ(picks[0].label, "fastest, most stable, knee");
  // Without run.json there is no report at all.
  test::TempDir empty;
  EXPECT_FALSE(load_run_data(empty.path(), data).is_ok());
}

TEST(ReportRunData, AnUnfinishedRunSaysHowFarItGotInOneLineAndItsFrontFilesInAnother) {
  // A run stopped at generation 3 of 50: front/ is only written when it finishes.
  test::TempDir tmp;
  tmp.write("run.json", R"({"problem":"walk","settings":{"generations":50}})");
  tmp.write("evaluations.jsonl",
            R"({"id":0,"generation":1,"reals":[0.5],"objectives":[4.0,1.25],"violation":0})"
            "\n");
  tmp.write("generations.jsonl", "{\"generation\":1}\n{\"generation\":2}\n{\"generation\":3}\n");
  tmp.write("pareto.csv", "f1,f2,g1\n3.0,2.0,0.4\n3.5,1.5,0.45\n4.0,1.25,0.5\n");
  RunData data;
  ASSERT_TRUE(load_run_data(tmp.path(), data).is_ok());
  EXPECT_EQ(data.generations_done, 3u);
  EXPECT_EQ(data.generations_planned, 50u);
  EXPECT_TRUE(data.unfinished());
  ASSERT_EQ(data.warnings.size(), 2u);
  EXPECT_EQ(data.warnings[0], "unfinished: generation 3 of 50 (stride optimise --out " +
                                  tmp.path().string() + " --resume continues it)");
  EXPECT_EQ(data.warnings[1],
            "front/000.json to front/002.json are missing (pareto.csv rows 0 to 2)");
  // The last generation logged: finished, and only the file still missing is named.
  tmp.write("run.json", R"({"problem":"walk","settings":{"generations":3}})");
  std::filesystem::create_directory(tmp.path() / "front");
  tmp.write("front/001.json", "{}");
  ASSERT_TRUE(load_run_data(tmp.path(), data).is_ok());
  EXPECT_FALSE(data.unfinished());
  ASSERT_EQ(data.warnings.size(), 2u);
  EXPECT_EQ(data.warnings[0], "front/000.json is missing (pareto.csv row 0)");
  EXPECT_EQ(data.warnings[1], "front/002.json is missing (pareto.csv row 2)");
}

TEST(ReportTables, ValidationJsonOfAnyShapeBecomesRows) {
  test::TempDir tmp;
  const auto file = tmp.write(
      "validation.json",
      R"({"format":"x","picks":[{"name":"knee","worlds":[{"world":"mujoco","kept":0.8,)"
      R"("time_s":13.4},{"world":"seed 101","kept":0.95}]}],"summary":{"kept_mean":0.875}})");
  const std::string html = validation_table_html(file);
  EXPECT_NE(html.find("id=\"validation-table\""), std::string::npos);
  for (const char* text : {"picks / knee / worlds / mujoco", "picks / knee / worlds / seed 101",
                           "summary", ">kept<", ">time_s<", ">0.8<", ">13.4<", ">0.875<"})
    EXPECT_NE(html.find(text), std::string::npos) << text;
  tmp.write("broken.json", "{\"picks\": [");
  EXPECT_NE(validation_table_html(tmp.path() / "broken.json").find("cannot be parsed"),
            std::string::npos);
  EXPECT_EQ(validation_table_html(tmp.path() / "absent.json"), "");
}

TEST(ReportReplay, Base64AndStickFigure) {
  EXPECT_EQ(base64("Man"), "TWFu");
  EXPECT_EQ(base64("Ma"), "TWE=");
  EXPECT_EQ(base64("M"), "TQ==");
  EXPECT_EQ(base64(""), "");
  sim::RobotModel model;
  ASSERT_TRUE(sim::RobotModel::load_file(sim::RobotModel::igus_path(), model));
  const sim::StickFigure f = sim::stick_figure(model);
  // 21 link origins, 4 sole points per foot, the head.
  EXPECT_EQ(f.point_count, 21 + 8 + 1);
  EXPECT_EQ(f.strokes.size(), model.joints().size() + 4);
  for (const auto& s : f.strokes) {
    EXPECT_LT(s.a, f.point_count);
    EXPECT_LT(s.b, f.point_count);
  }
  const std::vector<Eigen::Isometry3d> poses(model.links().size(), Eigen::Isometry3d::Identity());
  EXPECT_EQ(sim::stick_points(model, poses).size(), static_cast<std::size_t>(f.point_count));
  EXPECT_TRUE(sim::stick_points(model, {}).empty());
}

// An igus capture of `frames` frames standing still at the origin.
ReplayIndividual still_capture(const sim::RobotModel& model, int frames) {
  ReplayIndividual ind;
  ind.name = "Ind_O";
  ind.colour = "#1f77b4";
  ind.capture.period_s = 0.01;
  ind.capture.frame_every_ticks = 4;
  for (int f = 0; f < frames; ++f) {
    sim::PoseSnapshot s;
    s.time_s = 0.04 * f;
    s.links.assign(model.links().size(), Eigen::Isometry3d::Identity());
    s.links[0].translation() = Eigen::Vector3d(0.01 * f, 0, 0.5);
    s.joint_angles.assign(model.joints().size(), 0.25);
    s.left_foot_force = {0, 0, 30};
    s.right_foot_force = {1, 0, 35};
    ind.capture.frames.push_back(s);
  }
  return ind;
}

TEST(ReportReplay, TheSceneIsTheWorldsOwnGroundAndBall) {
  sim::RobotModel model;
  ASSERT_TRUE(sim::RobotModel::load_file(sim::RobotModel::igus_path(), model));
  sim::WorldOptions world;  // faithful: turf, 5 mm, a ball
  ReplayScene scene = replay_scene(world);
  EXPECT_EQ(scene.ground, "turf");
  EXPECT_DOUBLE_EQ(scene.grass_m, 0.005);
  EXPECT_DOUBLE_EQ(scene.ball_radius_m, world.ball.radius_m);
  ASSERT_TRUE(sim::parse_contact_kind("hard", world.contact));
  world.ball.present = false;
  scene = replay_scene(world);
  EXPECT_EQ(scene.ground, "hard");
  EXPECT_DOUBLE_EQ(scene.grass_m, 0.003);
  EXPECT_EQ(scene.ball_radius_m, 0.0);
  const nlohmann::json data = replay_data(model, {still_capture(model, 2)}, scene);
  EXPECT_EQ(data["ground"], "hard");
  EXPECT_DOUBLE_EQ(data["grass_m"].get<double>(), 0.003);
  world.contact = sim::ContactOptions::seed();
  world.contact.grass_damping_n_s_m = 55.0;  // a calibrated ground: no name of its own
  EXPECT_EQ(replay_scene(world).ground, "custom");
  EXPECT_DOUBLE_EQ(replay_scene(world).grass_m, 0.02);
}

// Sets $STRIDE_THREE_JS for one scope.
struct ThreeJsAt {
  explicit ThreeJsAt(const std::string& path) { ::setenv("STRIDE_THREE_JS", path.c_str(), 1); }
  ~ThreeJsAt() { ::unsetenv("STRIDE_THREE_JS"); }
};

TEST(ReportReplay3d, RobotFromTheCollisionGeometryAndCompactMotion) {
  sim::RobotModel model;
  ASSERT_TRUE(sim::RobotModel::load_file(sim::RobotModel::igus_path(), model));
  std::string problem;
  const nlohmann::json robot = robot3d_model(model, problem);
  ASSERT_FALSE(robot.is_null()) << problem;
  EXPECT_EQ(problem, "");
  EXPECT_EQ(robot["links"].size(), model.links().size());
  EXPECT_EQ(robot["joints"].size(), model.joints().size());
  EXPECT_EQ(robot["feet"][0], model.link_index("left_foot_link"));
  EXPECT_EQ(robot["feet"][1], model.link_index("right_foot_link"));
  EXPECT_EQ(robot["values_per_frame"], 3 + 4 + 20 + 6 + 3);
  // Each foot: its sole box and 4 studs; the head: a sphere; the trunk: a box.
  const auto& foot = robot["links"][model.link_index("left_foot_link")];
  EXPECT_EQ(foot["boxes"].size(), 1u);
  EXPECT_EQ(foot["spheres"].size(), 4u);
  for (const auto& stud : foot["spheres"]) EXPECT_EQ(stud[4], 1);
  EXPECT_EQ(robot["links"][model.link_index("head_link")]["spheres"].size(), 1u);
  EXPECT_EQ(robot["links"][0]["boxes"][0].size(), 10u);

  // 72 bytes per frame (96 base64 digits).
  const ReplayIndividual ind = still_capture(model, 25);
  const std::string motion = robot3d_motion(model, ind, problem);
  EXPECT_EQ(problem, "");
  EXPECT_EQ(motion.size(), 25u * 96u);

  // No frames, or joint angles of another robot: said, no data.
  ReplayIndividual empty = ind;
  empty.capture.frames.clear();
  EXPECT_EQ(robot3d_motion(model, empty, problem), "");
  EXPECT_NE(problem.find("Ind_O: no trajectory was recorded"), std::string::npos) << problem;
  ReplayIndividual other = ind;
  other.capture.frames[3].joint_angles.resize(12);
  EXPECT_EQ(robot3d_motion(model, other, problem), "");
  EXPECT_NE(problem.find("12 joint angles, the robot model 20"), std::string::npos) << problem;
}

TEST(ReportReplay3d, NothingToDrawIsSaidNotDrawn) {
  // A URDF whose links have no box or sphere to draw.
  sim::RobotModel bare;
  ASSERT_TRUE(sim::RobotModel::load_string(
      R"(<robot name="bare"><link name="a"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
<link name="b"><inertial><mass value="1"/><inertia ixx="0.01" iyy="0.01" izz="0.01" ixy="0" ixz="0" iyz="0"/></inertial></link>
<joint name="j" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint></robot>)",
      "bare.urdf", bare));
  std::string problem;
  EXPECT_TRUE(robot3d_model(bare, problem).is_null());
  EXPECT_NE(problem.find("(bare) has no box or sphere collision geometry"), std::string::npos)
      << problem;
  EXPECT_TRUE(robot3d_model(sim::RobotModel{}, problem).is_null());
  EXPECT_NE(problem.find("could not be loaded"), std::string::npos) << problem;
}

TEST(ReportReplay3d, SectionSaysWhatIsMissingWithOneWarning) {
  test::TempDir tmp;
  sim::RobotModel model;
  ASSERT_TRUE(sim::RobotModel::load_file(sim::RobotModel::igus_path(), model));
  const ReplayIndividual ind = still_capture(model, 10);
  ReplayIndividual empty = ind;
  empty.name = "knee";
  empty.capture.frames.clear();
  auto page_of = [&](const std::vector<ReplayIndividual>& inds,
                     std::vector<std::string>& warnings) {
    HtmlPage page("t", "s");
    add_replay_section(page, "", model, inds, ReplayScene{}, warnings);
    return page.str();
  };
  {
    // three.js missing: the 3D view says so; the 2D replay stays.
    ThreeJsAt three((tmp.path() / "absent.js").string());
    std::vector<std::string> warnings;
    const std::string html = page_of({ind}, warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("three.js not found at " + (tmp.path() / "absent.js").string()),
              std::string::npos);
    EXPECT_NE(html.find("The 3D view is unavailable: three.js not found"), std::string::npos);
    EXPECT_NE(html.find("id=\"replay-cards\""), std::string::npos);
    EXPECT_EQ(html.find("id=\"replay3d-js\""), std::string::npos);
  }
  const std::string fake = tmp.write("three.min.js", "var THREE={REVISION:'111'};").string();
  ThreeJsAt three(fake);
  {
    // Everything there: three.js and the 3D script inlined, no warning.
    std::vector<std::string> warnings;
    const std::string html = page_of({ind}, warnings);
    EXPECT_TRUE(warnings.empty());
    EXPECT_NE(html.find("<script id=\"three-js\">"), std::string::npos);
    EXPECT_NE(html.find("var THREE={REVISION:'111'};"), std::string::npos);
    EXPECT_NE(html.find("<script id=\"replay3d-js\">"), std::string::npos);
    EXPECT_NE(html.find("\"robot3d\":"), std::string::npos);
    EXPECT_NE(html.find("data-state=\"loading\""), std::string::npos);
  }
  {
    // One individual without a trajectory: left out and said; none: the view says so.
    std::vector<std::string> warnings;
    std::string html = page_of({ind, empty}, warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("leaves out knee: no trajectory was recorded"), std::string::npos);
    EXPECT_NE(html.find("<script id=\"replay3d-js\">"), std::string::npos);
    EXPECT_NE(html.find("class=\"missing\""), std::string::npos);
    warnings.clear();
    html = page_of({empty}, warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(html.find("The 3D view is unavailable: knee: no trajectory was recorded."),
              std::string::npos);
    EXPECT_EQ(html.find("id=\"replay3d-js\""), std::string::npos);
  }
}

}  // namespace
}  // namespace stride::opt::report
