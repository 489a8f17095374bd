// Script parameters and the seed's kick genome (frames 2..N-1): names, bounds, and the round
// trip genome -> parameter store -> played targets -> genome.
#include <gtest/gtest.h>

#include "stride/firmware/script/script_engine.hpp"
#include "stride/firmware/script/script_genome.hpp"
#include "stride/hal/scripted_robot.hpp"

namespace stride::fw {
namespace {

constexpr std::int64_t kPeriodNs = 10'000'000;

struct Stock {
  ParameterStore params;
  ScriptEngine engine{kPeriodNs, params};
  Stock() {
    const Status status = engine.load_folder(default_script_folder());
    if (!status) ADD_FAILURE() << status.message();
  }
  const Script& kick() const {
    return engine.script(static_cast<std::size_t>(engine.find("kick_right")));
  }
};

TEST(ScriptParameters, EveryTargetIsAParameterBoundedByTheServoLimits) {
  Stock s;
  const auto handle = s.params.find("script.kick_right.frame2.r_knee.position");
  ASSERT_TRUE(handle.has_value());
  const ParamSpec& spec = s.params.spec(*handle);
  EXPECT_DOUBLE_EQ(spec.default_value, 0.2945);
  EXPECT_DOUBLE_EQ(s.params.value(*handle), 0.2945);
  const ServoSpec& knee = ServoTable::defaults()[*ServoTable::defaults().index_of("r_knee")];
  EXPECT_DOUBLE_EQ(spec.min, knee.min_rad);
  EXPECT_DOUBLE_EQ(spec.max, knee.max_rad);
  EXPECT_EQ(spec.unit, "rad");
  EXPECT_TRUE(s.params.find("script.kick_right.frame1.r_knee.position").has_value());
  EXPECT_TRUE(s.params.find("script.kick_left.frame6.l_ankle_roll.position").has_value());
  EXPECT_TRUE(s.params.find("script.stand.frame1.l_knee.position").has_value());
  EXPECT_FALSE(s.params.find("script.kick_right.frame7.r_knee.position").has_value());
  EXPECT_FALSE(s.params.find("script.kick_right.frame2.head_yaw.position").has_value());
  // A write outside the servo limits is refused, naming the parameter.
  const Status bad = s.params.stage("script.kick_right.frame2.r_knee.position", 3.0);
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.message().find("script.kick_right.frame2.r_knee.position"), std::string::npos);
}

TEST(ScriptGenome, KickGenomeIsFramesTwoToFiveInFileOrder) {
  Stock s;
  std::vector<ScriptGene> genes;
  ASSERT_TRUE(kick_genome(s.params, s.kick(), genes));
  ASSERT_EQ(genes.size(), 4u * 18u);  // frames 2..5 of 6, 18 servos each (no head)
  EXPECT_EQ(genes.front().parameter, "script.kick_right.frame2.r_shoulder_pitch.position");
  EXPECT_EQ(genes[18].parameter, "script.kick_right.frame3.r_shoulder_pitch.position");
  EXPECT_EQ(genes.back().parameter, "script.kick_right.frame5.l_ankle_roll.position");
  for (const ScriptGene& g : genes) {
    EXPECT_LE(g.min, g.seed);
    EXPECT_GE(g.max, g.seed);
    EXPECT_LE(g.max - g.min, 1.0 + 1e-12) << g.parameter;
  }
  // Seed +- 0.5 rad, clipped to the servo limits (r_ankle_roll frame 2 is 0.6276, limit 0.7).
  const auto r_knee = std::find_if(genes.begin(), genes.end(), [](const ScriptGene& g) {
    return g.parameter == "script.kick_right.frame3.r_knee.position";
  });
  ASSERT_NE(r_knee, genes.end());
  EXPECT_DOUBLE_EQ(r_knee->min, 0.8975 - 0.5);
  EXPECT_DOUBLE_EQ(r_knee->max, 0.8975 + 0.5);
  const auto ankle = std::find_if(genes.begin(), genes.end(), [](const ScriptGene& g) {
    return g.parameter == "script.kick_right.frame2.r_ankle_roll.position";
  });
  ASSERT_NE(ankle, genes.end());
  EXPECT_DOUBLE_EQ(ankle->max, 0.7);
  EXPECT_DOUBLE_EQ(ankle->min, 0.6276 - 0.5);
}

TEST(ScriptGenome, RoundTripThroughStoreAndPlayback) {
  Stock s;
  std::vector<ScriptGene> genes;
  ASSERT_TRUE(kick_genome(s.params, s.kick(), genes));
  // A genome away from the seed: each gene at a different fraction of its range.
  std::vector<double> reals(genes.size());
  for (std::size_t i = 0; i < genes.size(); ++i) {
    const double fraction = static_cast<double>((i * 37) % 101) / 100.0;
    reals[i] = genes[i].min + fraction * (genes[i].max - genes[i].min);
  }
  std::vector<ParamWrite> writes;
  ASSERT_TRUE(genome_writes(genes, reals, writes));
  ASSERT_TRUE(s.params.stage(writes));
  ASSERT_TRUE(s.params.apply_staged());
  std::vector<double> back;
  ASSERT_TRUE(genome_from_store(s.params, genes, back));
  EXPECT_EQ(back, reals);

  // The engine plays the genome: in frame k the commanded goals are frame k's genes.
  ASSERT_TRUE(s.engine.select(s.engine.find("kick_right")));
  hal::CommandFrame out{};
  const hal::SensorFrame sensors = hal::ScriptedRobot::standing_frame();
  s.engine.start(sensors, out, 0);
  const Script& kick = s.kick();
  for (std::size_t frame = 0; frame < kick.frames.size(); ++frame) {
    const hal::Tick previous_deadline = frame == 0 ? 0 : s.engine.deadline(frame - 1);
    s.engine.step(sensors, previous_deadline, out);
    for (std::size_t j = 0; j < kick.frames[frame].targets.size(); ++j) {
      const ScriptTarget& t = kick.frames[frame].targets[j];
      const double expected =
          (frame >= 1 && frame <= 4) ? reals[(frame - 1) * 18 + j] : t.position_rad;
      EXPECT_DOUBLE_EQ(out.servos[t.servo].position_rad, expected)
          << "frame " << frame + 1 << " target " << j;
    }
  }
  // The script data itself is unchanged (the store holds the genome).
  EXPECT_DOUBLE_EQ(kick.frames[2].targets[12].position_rad, 0.8975);
}

TEST(ScriptGenome, BadGenomesAreRefusedAndChangeNothing) {
  Stock s;
  std::vector<ScriptGene> genes;
  ASSERT_TRUE(kick_genome(s.params, s.kick(), genes));
  std::vector<double> reals;
  for (const ScriptGene& g : genes) reals.push_back(g.seed);
  std::vector<ParamWrite> writes;
  reals[5] = genes[5].max + 0.01;
  const Status out_of_bounds = genome_writes(genes, reals, writes);
  ASSERT_FALSE(out_of_bounds);
  EXPECT_NE(out_of_bounds.message().find(genes[5].parameter), std::string::npos);
  reals.pop_back();
  EXPECT_FALSE(genome_writes(genes, reals, writes));
  EXPECT_TRUE(writes.empty());
  EXPECT_FALSE(script_genome(s.params, s.kick(), 0, 3, 0.5, genes));
  EXPECT_FALSE(script_genome(s.params, s.kick(), 2, 7, 0.5, genes));
  EXPECT_FALSE(script_genome(s.params, s.kick(), 2, 5, 0.0, genes));
  ParameterStore empty;
  EXPECT_FALSE(kick_genome(empty, s.kick(), genes));
}

}  // namespace
}  // namespace stride::fw
