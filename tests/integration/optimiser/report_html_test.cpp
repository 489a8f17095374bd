// report.html end to end: a short walk run, `stride report` re-running Ind_O and the picks (the
// re-run scores exactly what the run logged), every section on the page, no network resource;
// the replays draw the run's own ground and robot (its world in run.json); run directories
// with pieces missing give a page and one warning line, never a failure;
// `stride sim --html` writes the one-episode page, with the 3D replay when three.js is there and
// a note and one warning line when it is not. (The page in a real browser:
// tests/browser/.)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>

#include <nlohmann/json.hpp>

#include "child_process.hpp"
#include "temp_dir.hpp"

namespace stride {
namespace {

namespace fs = std::filesystem;
const std::string kStride = std::string(STRIDE_BIN_DIR) + "/stride";
const std::string kConfigs = std::string(STRIDE_SOURCE_DIR) + "/optimiser/configs/";

struct Result {
  int code = -1;
  std::string out, err;
};

// `env` sets extra environment variables ("NAME=value") for the child.
Result stride(const std::vector<std::string>& args, const fs::path& dir,
              const std::vector<std::string>& env = {}) {
  std::vector<std::string> argv;
  if (!env.empty()) argv.push_back("/usr/bin/env");
  argv.insert(argv.end(), env.begin(), env.end());
  argv.push_back(kStride);
  argv.insert(argv.end(), args.begin(), args.end());
  Result r;
  r.code = test::wait_exit(test::spawn(argv, dir / "out.txt", dir / "err.txt"));
  r.out = test::slurp(dir / "out.txt");
  r.err = test::slurp(dir / "err.txt");
  return r;
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// One short walk run shared by the tests (2 s episodes, goal 0.3 m, pop 4, 2 generations).
class ReportHtml : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    tmp_ = new test::TempDir();
    std::ifstream in(kConfigs + "walk.json");
    nlohmann::json c = nlohmann::json::parse(in);
    c["pop"] = 4;
    c["generations"] = 2;
    c["duration_s"] = 2.0;
    c["goal_distance_m"] = 0.3;
    c["pm"] = 0.2;
    c["validate"] = {{"seeds", 2}};  // stride optimise validates at the end: keep it short
    std::ofstream(tmp_->path() / "walk.json") << c.dump(1);
    run_ = tmp_->path() / "run";
    const Result r = stride({"optimise", "--config", (tmp_->path() / "walk.json").string(), "--out",
                             run_.string(), "--jobs", "2"},
                            tmp_->path());
    ASSERT_EQ(r.code, 0) << r.err;
  }
  static void TearDownTestSuite() { delete tmp_; }
  static fs::path copy_run(const std::string& name) {
    const fs::path to = tmp_->path() / name;
    fs::copy(run_, to, fs::copy_options::recursive);
    return to;
  }
  static test::TempDir* tmp_;
  static fs::path run_;
};
test::TempDir* ReportHtml::tmp_ = nullptr;
fs::path ReportHtml::run_;

TEST_F(ReportHtml, EverySectionAndTheReRunScoresWhatTheRunLogged) {
  const fs::path dir = copy_run("complete");
  const Result r = stride({"report", dir.string(), "--json"}, tmp_->path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.err, "");  // nothing missing, no warning
  const auto summary = nlohmann::json::parse(r.out);
  EXPECT_EQ(summary["report"], (dir / "report.html").string());
  EXPECT_TRUE(summary["warnings"].empty());
  const std::string page = test::slurp(dir / "report.html");
  EXPECT_EQ(page.size(), summary["report_bytes"].get<std::size_t>());
  EXPECT_LT(page.size(), 5u << 20);
  // three.js (Debian's libjs-three) inlined once for the 3D replay; the checks below look at
  // the rest of the page (three.js itself names the XHTML namespace).
  const std::size_t three = page.find("<script id=\"three-js\">");
  ASSERT_NE(three, std::string::npos) << "three.js not inlined (libjs-three installed?)";
  EXPECT_NE(page.find("REVISION", three), std::string::npos);
  const std::size_t three_end = page.find("</script>", three);
  const std::string html = page.substr(0, three) + page.substr(three_end);
  EXPECT_EQ(count(html, "<script id=\"replay3d-js\">"), 1);
  for (const char* id : {"settings", "picks", "pareto", "hypervolume", "accelerometer", "poses",
                         "replay", "parameters"})
    EXPECT_EQ(count(html, std::string("data-section=\"") + id + "\""), 1) << id;
  // The validation.json that stride optimise wrote at the end of the run, as a table.
  EXPECT_EQ(count(html, "data-section=\"validation\""), 1);
  EXPECT_EQ(count(html, "id=\"validation-table\""), 1);
  EXPECT_EQ(count(html, "class=\"missing\""), 0);
  // Ind_O and each distinct pick were re-run in the run's world and scored exactly as logged.
  const int rows = count(html, "<tr><td class=\"name\"><span class=\"swatch\"");
  EXPECT_GE(rows, 2);
  EXPECT_EQ(count(html, "(same as logged)"), rows);
  EXPECT_EQ(count(html, "(differs)"), 0);
  // Self-contained: nothing fetched from anywhere (the only URL is the SVG namespace).
  EXPECT_FALSE(std::regex_search(html, std::regex(R"re((src|href)\s*=\s*"(https?:)?//)re")));
  EXPECT_EQ(count(html, "url("), 0);
  EXPECT_EQ(count(html, "http"), count(html, "http://www.w3.org/2000/svg"));
  // Replay data for every individual, and Ind_O marked on the front.
  const std::size_t data = html.find("<script type=\"application/json\" id=\"replay-data\">");
  ASSERT_NE(data, std::string::npos);
  const std::size_t start = html.find('>', data) + 1;
  const auto replay =
      nlohmann::json::parse(html.substr(start, html.find("</script>", start) - start));
  EXPECT_EQ(replay["individuals"].size(), static_cast<std::size_t>(rows));
  for (const auto& ind : replay["individuals"]) {
    EXPECT_GT(ind["frames"].get<int>(), 5);
    // The 3D motion: 25 frames per second, 36 int16 per frame (96 base64 digits).
    EXPECT_EQ(ind["motion_frames"], ind["frames"]);
    EXPECT_EQ(ind["motion"].get<std::string>().size(), ind["frames"].get<std::size_t>() * 96);
  }
  EXPECT_NEAR(replay["frame_dt"].get<double>(), 0.04, 1e-12);
  EXPECT_EQ(replay["robot3d"]["links"].size(), 21u);
  // The run's own world: walk.json's faithful world is turf (5 mm) with the igus robot.
  EXPECT_EQ(replay["ground"], "turf");
  EXPECT_DOUBLE_EQ(replay["grass_m"].get<double>(), 0.005);
  EXPECT_EQ(replay["robot3d"]["name"], "igus_op");
  // The validation's worlds table, read from each world's options: the grounds by name.
  const std::size_t worlds = html.find("<table id=\"validation-worlds\">");
  ASSERT_NE(worlds, std::string::npos);
  const std::string table = html.substr(worlds, html.find("</table>", worlds) - worlds);
  for (const char* ground : {"<td>turf</td>", "<td>soft</td>", "<td>hard</td>"})
    EXPECT_NE(table.find(ground), std::string::npos) << ground << " in " << table;
  const std::string svg = test::slurp(dir / "pareto_by_generation.svg");
  EXPECT_NE(svg.find(">Ind_O<"), std::string::npos);
  EXPECT_NE(svg.find("front/000.json"), std::string::npos);  // tooltips name the front files
  // The same run reported twice gives the same page (deterministic re-runs).
  ASSERT_EQ(stride({"report", dir.string()}, tmp_->path()).code, 0);
  EXPECT_EQ(test::slurp(dir / "report.html"), page);
}

// The replay data of a report page.
nlohmann::json replay_data_of(const std::string& page) {
  const std::size_t data = page.find("<script type=\"application/json\" id=\"replay-data\">");
  if (data == std::string::npos) return nullptr;
  const std::size_t start = page.find('>', data) + 1;
  return nlohmann::json::parse(page.substr(start, page.find("</script>", start) - start));
}

TEST_F(ReportHtml, TheReplaysDrawTheRunsOwnGroundAndRobot) {
  // The run's world in run.json changed to the hard ground and a URDF of another name: the
  // re-runs run there, and the replays draw that ground and that robot.
  const fs::path dir = copy_run("hard");
  const fs::path urdf = tmp_->path() / "renamed.urdf";
  std::string robot = test::slurp(fs::path(STRIDE_SOURCE_DIR) / "sim_hal/models/igus_op.urdf");
  const std::string name = "<robot name=\"igus_op\">";
  ASSERT_NE(robot.find(name), std::string::npos);
  robot.replace(robot.find(name), name.size(), "<robot name=\"igus_renamed\">");
  std::ofstream(urdf) << robot;
  nlohmann::json run = nlohmann::json::parse(test::slurp(dir / "run.json"));
  run["task"]["world"]["contact"] = "hard";
  run["task"]["world"]["urdf"] = urdf.string();
  std::ofstream(dir / "run.json", std::ios::trunc) << run.dump(1);
  const Result r = stride({"report", dir.string()}, tmp_->path());
  ASSERT_EQ(r.code, 0) << r.err;
  const nlohmann::json replay = replay_data_of(test::slurp(dir / "report.html"));
  ASSERT_TRUE(replay.is_object());
  EXPECT_EQ(replay["ground"], "hard");
  EXPECT_DOUBLE_EQ(replay["grass_m"].get<double>(), 0.003);
  EXPECT_EQ(replay["robot3d"]["name"], "igus_renamed");
  EXPECT_EQ(replay["ball_radius_m"], 0.0);  // a walk: no ball
}

TEST_F(ReportHtml, MissingPiecesGiveAPageAndOneWarningLine) {
  // A run that has not evaluated anything yet: run.json only, an empty log.
  const fs::path empty = tmp_->path() / "empty";
  fs::create_directories(empty);
  fs::copy_file(run_ / "run.json", empty / "run.json");
  std::ofstream(empty / "evaluations.jsonl").flush();
  Result r = stride({"report", empty.string()}, tmp_->path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(count(r.err, "\n"), 1) << r.err;
  EXPECT_NE(r.err.find("warning: evaluations.jsonl is empty"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("pareto.csv is missing"), std::string::npos) << r.err;
  std::string html = test::slurp(empty / "report.html");
  EXPECT_NE(html.find("No evaluations logged yet."), std::string::npos);
  EXPECT_NE(html.find("<li>generations.jsonl is missing</li>"), std::string::npos);
  EXPECT_NE(html.find("No front member to compare with Ind_O."), std::string::npos);
  EXPECT_EQ(count(html, "</html>"), 1);

  // A log torn in its last line and a front file deleted: said, and the file rewritten.
  const fs::path torn = copy_run("torn");
  std::string log = test::slurp(torn / "evaluations.jsonl");
  log.resize(log.size() - 40);
  std::ofstream(torn / "evaluations.jsonl", std::ios::trunc) << log;
  fs::remove(torn / "front/000.json");
  r = stride({"report", torn.string()}, tmp_->path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(count(r.err, "\n"), 1) << r.err;
  EXPECT_NE(r.err.find("evaluations.jsonl: 1 damaged line(s) skipped"), std::string::npos);
  EXPECT_NE(r.err.find("front/000.json is missing (pareto.csv row 0); rewritten"),
            std::string::npos);
  EXPECT_TRUE(fs::exists(torn / "front/000.json"));
  html = test::slurp(torn / "report.html");
  EXPECT_NE(html.find("damaged line(s) skipped"), std::string::npos);
  EXPECT_NE(html.find("data-section=\"replay\""), std::string::npos);

  // validation.json: shown as a table when readable, said when not.
  std::ofstream(torn / "validation.json")
      << R"({"picks":[{"name":"knee","worlds":[{"world":"mujoco","kept":0.81}]}]})";
  ASSERT_EQ(stride({"report", torn.string()}, tmp_->path()).code, 0);
  html = test::slurp(torn / "report.html");
  EXPECT_NE(html.find("id=\"validation-table\""), std::string::npos);
  EXPECT_NE(html.find("picks / knee / worlds / mujoco"), std::string::npos);
  std::ofstream(torn / "validation.json", std::ios::trunc) << "{\"picks\": [";
  ASSERT_EQ(stride({"report", torn.string()}, tmp_->path()).code, 0);
  EXPECT_NE(test::slurp(torn / "report.html").find("validation.json exists but cannot be parsed"),
            std::string::npos);

  // three.js missing when the report is written: the page says the 3D view is unavailable (the
  // 2D replay stays), one warning line.
  const fs::path flat = copy_run("no_three");
  r = stride({"report", flat.string()}, tmp_->path(), {"STRIDE_THREE_JS=/nonexistent/three.js"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(count(r.err, "\n"), 1) << r.err;
  EXPECT_NE(r.err.find("the 3D replay is unavailable: three.js not found at /nonexistent/three.js"),
            std::string::npos)
      << r.err;
  html = test::slurp(flat / "report.html");
  EXPECT_NE(html.find("<p class=\"missing\">The 3D view is unavailable: three.js not found"),
            std::string::npos);
  EXPECT_NE(html.find("<li>the 3D replay is unavailable: three.js not found"), std::string::npos);
  EXPECT_NE(html.find("id=\"replay-cards\""), std::string::npos);
  EXPECT_EQ(html.find("<script id=\"three-js\">"), std::string::npos);
  EXPECT_EQ(count(html, "</html>"), 1);

  // No run.json: bad input, one line, exit 2, no page.
  const fs::path none = tmp_->path() / "none";
  fs::create_directories(none);
  r = stride({"report", none.string()}, tmp_->path());
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(count(r.err, "\n"), 1) << r.err;
  EXPECT_FALSE(fs::exists(none / "report.html"));
}

TEST(StrideSimHtml, WritesTheReplayOfOneEpisode) {
  test::TempDir tmp;
  const fs::path page = tmp.path() / "stand.html";
  Result r = stride({"sim", "stand", "--duration", "1", "--html", page.string()}, tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string html = test::slurp(page);
  for (const char* id : {"episode", "accelerometer", "poses", "replay"})
    EXPECT_EQ(count(html, std::string("data-section=\"") + id + "\""), 1) << id;
  EXPECT_NE(html.find("id=\"replay-data\""), std::string::npos);
  EXPECT_NE(html.find("<script id=\"replay3d-js\">"), std::string::npos);
  EXPECT_EQ(r.err, "");
  // Without three.js: the page says the 3D view is unavailable, one warning line, exit 0.
  const fs::path flat = tmp.path() / "flat.html";
  r = stride({"sim", "stand", "--duration", "0.5", "--html", flat.string()}, tmp.path(),
             {"STRIDE_THREE_JS=/nonexistent/three.min.js"});
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(count(r.err, "\n"), 1) << r.err;
  EXPECT_NE(r.err.find("stride sim: warning: the 3D replay is unavailable: three.js not found at "
                       "/nonexistent/three.min.js"),
            std::string::npos)
      << r.err;
  const std::string flat_html = test::slurp(flat);
  EXPECT_NE(flat_html.find("The 3D view is unavailable: three.js not found"), std::string::npos);
  EXPECT_NE(flat_html.find("id=\"replay-cards\""), std::string::npos);
  EXPECT_EQ(count(flat_html, "</html>"), 1);
  // A URDF the page cannot draw (no collision geometry): the page says so, one warning line.
  std::string urdf = test::slurp(fs::path(STRIDE_SOURCE_DIR) / "sim_hal/models/igus_op.urdf");
  urdf = std::regex_replace(urdf, std::regex(R"(<collision[^]*?</collision>)"), "");
  std::ofstream(tmp.path() / "bare.urdf") << urdf;
  const fs::path bare = tmp.path() / "bare.html";
  r = stride({"sim", "stand", "--duration", "0.2", "--urdf", (tmp.path() / "bare.urdf").string(),
              "--html", bare.string()},
             tmp.path());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(count(r.err, "\n"), 1) << r.err;
  EXPECT_NE(r.err.find("has no box or sphere collision geometry to draw"), std::string::npos)
      << r.err;
  EXPECT_NE(test::slurp(bare).find("The 3D view is unavailable: the robot model (igus_op) has no "
                                   "box or sphere collision geometry to draw."),
            std::string::npos);
  r = stride({"sim", "stand", "--duration", "0.2", "--html", "/nonexistent/dir/x.html"},
             tmp.path());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("/nonexistent/dir"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace stride
