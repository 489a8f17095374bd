// Report building blocks: 1-2-5 ticks, charts with the legend outside the plot and tooltips,
// the tolerant run-directory and validation.json readers, base64 and the stick figure.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "stride/optimiser/report/html_replay.hpp"
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

}  // namespace
}  // namespace stride::opt::report
