// Walk-optimisation speed (plain program, Google Benchmark not needed): evaluates the first
// generation of the seed's walk run (optimiser/configs/walk.json, pop 40, seed 300: Ind_O plus
// 39 mutants) with 1 and with 2 threads, and reports evaluations per second, the 2-thread
// speed-up, the share of an evaluation spent outside the episode loop's physics (set-up of the
// firmware and world + Controller::step) and the estimated time of the whole 2,000-evaluation
// run at the measured rate. The 1- and 2-thread passes alternate `repeats` times and the
// median speed-up is reported (one pair of passes varies by +-5 % on a shared VM).
// Usage: bench_optimiser_walk [population, default 40] [repeats, default 3]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "stride/optimiser/nsga2/evaluator.hpp"
#include "stride/optimiser/nsga2/nsga2.hpp"
#include "stride/optimiser/tasks/robot_task.hpp"

using namespace stride::opt;

int main(int argc, char** argv) {
  TaskConfig config;
  if (auto s =
          load_task_config(std::string(STRIDE_SOURCE_DIR) + "/optimiser/configs/walk.json", config);
      !s) {
    std::fprintf(stderr, "%s\n", s.message().c_str());
    return 1;
  }
  if (argc > 1) config.settings.pop_size = std::atoi(argv[1]);
  const int repeats = argc > 2 ? std::max(1, std::atoi(argv[2])) : 3;
  const RobotTask task(config);
  std::unique_ptr<Nsga2> engine;
  if (auto s = Nsga2::create(config.settings, task.shape(), task.start_genome(), engine); !s) {
    std::fprintf(stderr, "%s\n", s.message().c_str());
    return 1;
  }
  const std::vector<Candidate> batch = engine->ask();

  // Serial pass with the time split of every episode.
  double setup = 0, controller = 0, loop = 0, sim_time = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (const auto& c : batch) {
    EpisodeScore s;
    if (auto st = task.run_trial(c.genome, 0, s); !st) {
      std::fprintf(stderr, "%s\n", st.message().c_str());
      return 1;
    }
    setup += s.setup_s, controller += s.controller_s, loop += s.wall_time_s,
        sim_time += s.sim_time_s;
  }
  const double serial_s =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  auto timed = [&](int jobs) {
    ThreadPoolEvaluator evaluator(jobs);
    const auto start = std::chrono::steady_clock::now();
    evaluator.evaluate(task, batch, [](std::size_t, EvaluationOutcome) {});
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  const double n = static_cast<double>(batch.size());
  std::printf("walk evaluations: %zu genomes, %.1f s simulated in total (%.2f s each on average)\n",
              batch.size(), sim_time, sim_time / n);
  std::vector<double> ones, twos, ratios;
  for (int r = 0; r < repeats; ++r) {
    ones.push_back(timed(1));
    twos.push_back(timed(2));
    ratios.push_back(ones.back() / twos.back());
    std::printf("pass %d: 1 thread %.3f evaluations/s, 2 threads %.3f evaluations/s: %.2fx\n",
                r + 1, n / ones.back(), n / twos.back(), ratios.back());
  }
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const std::size_t m = v.size() / 2;
    return v.size() % 2 == 1 ? v[m] : 0.5 * (v[m - 1] + v[m]);
  };
  const double one = median(ones), two = median(twos);
  std::printf("1 thread : %.3f evaluations/s (%.3f s per evaluation, median of %d)\n", n / one,
              one / n, repeats);
  std::printf("2 threads: %.3f evaluations/s, speed-up %.2fx (median of the %d passes' ratios)\n",
              n / two, median(ratios), repeats);
  std::printf(
      "serial pass %.2f s: set-up %.1f %%, Controller::step %.2f %%, episode loop %.1f %% "
      "(physics + metrics), other %.1f %%\n",
      serial_s, 100 * setup / serial_s, 100 * controller / serial_s,
      100 * (loop - controller) / serial_s, 100 * (serial_s - setup - loop) / serial_s);
  std::printf(
      "outside the episode loop's physics (set-up + controller + other): %.1f %% of an "
      "evaluation\n",
      100 * (serial_s - (loop - controller)) / serial_s);
  std::printf(
      "estimated 2,000-evaluation walk run at the 2-thread rate: %.0f s (if later generations "
      "simulate as long as the first)\n",
      2000.0 / (n / two));
  return 0;
}
