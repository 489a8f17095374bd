// Optimiser quality (issue 7, point 9): NSGA-II with pop 100, 250 generations, pc 0.9, etaC 20,
// pm 1/n, etaM 20 on every test problem, 11 seeds; prints the median, worst and best ratio of the
// normalised hypervolume (reference point 1.1) to the true front's, the median IGD and the
// median number of feasible population members, as a Markdown table.
// Usage: bench_optimiser_quality [--seeds N] [--generations N] [--problems a,b,...]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "stride/optimiser/nsga2/nsga2.hpp"
#include "stride/optimiser/problems/test_problems.hpp"
#include "stride/optimiser/run/optimisation_run.hpp"

namespace {

using namespace stride::opt;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

double target_for(const std::string& name) {
  if (name == "zdt1" || name == "zdt2" || name == "zdt3") return 0.99;
  if (name == "zdt4") return 0.985;
  if (name == "zdt6") return 0.975;
  return 0.0;
}

}  // namespace

int main(int argc, char** argv) {
  int seeds = 11;
  int generations = 250;
  std::vector<std::string> names = test_problem_names();
  for (int i = 1; i + 1 < argc; i += 2) {
    if (std::strcmp(argv[i], "--seeds") == 0) seeds = std::atoi(argv[i + 1]);
    if (std::strcmp(argv[i], "--generations") == 0) generations = std::atoi(argv[i + 1]);
    if (std::strcmp(argv[i], "--problems") == 0) {
      names.clear();
      std::stringstream in(argv[i + 1]);
      std::string item;
      while (std::getline(in, item, ',')) names.push_back(item);
    }
  }
  std::printf("pop 100, %d generations, pc 0.9, etaC 20, pm 1/n, etaM 20, seeds 1..%d\n\n",
              generations, seeds);
  std::printf(
      "| problem | HV ratio median | worst | best | target | IGD median | feasible "
      "(median) | s/run |\n|---|---|---|---|---|---|---|---|\n");
  int failures = 0;
  for (const std::string& name : names) {
    const auto problem = make_test_problem(name);
    if (!problem) {
      std::fprintf(stderr, "unknown problem %s\n", name.c_str());
      return 2;
    }
    const auto reference = problem->reference();
    std::vector<double> ratios;
    std::vector<double> igds;
    std::vector<double> feasible;
    const auto started = std::chrono::steady_clock::now();
    for (int seed = 1; seed <= seeds; ++seed) {
      Nsga2Settings s;
      s.seed = static_cast<std::uint64_t>(seed);
      s.pop_size = 100;
      s.generations = generations;
      s.real_cross_prob = 0.9;
      s.eta_c = 20;
      s.eta_m = 20;
      s.real_mut_prob = 1.0 / static_cast<double>(problem->shape().reals.size());
      std::unique_ptr<Nsga2> engine;
      if (auto st = Nsga2::create(s, problem->shape(), std::nullopt, engine); !st) {
        std::fprintf(stderr, "%s\n", st.message().c_str());
        return 1;
      }
      while (!engine->finished()) {
        for (const Candidate& c : engine->ask()) {
          if (!engine->tell(c.id, problem->evaluate(c.genome)).is_ok()) return 1;
        }
        if (!engine->advance().is_ok()) return 1;
      }
      const GenerationRecord r = measure(*problem, engine->population(), reference);
      ratios.push_back(r.hypervolume_ratio.value_or(0.0));
      igds.push_back(r.igd.value_or(1e9));
      feasible.push_back(r.feasible);
    }
    const double seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() / seeds;
    const double med = median(ratios);
    const double target = target_for(name);
    const bool ok = med >= target;
    if (!ok) ++failures;
    char target_text[32] = "-";
    if (target > 0) std::snprintf(target_text, sizeof target_text, ">= %.1f %%", 100 * target);
    std::printf("| %s | %.2f %% %s | %.2f %% | %.2f %% | %s | %.5f | %.0f | %.2f |\n", name.c_str(),
                100 * med, target > 0 ? (ok ? "(met)" : "(NOT met)") : "",
                100 * *std::min_element(ratios.begin(), ratios.end()),
                100 * *std::max_element(ratios.begin(), ratios.end()), target_text, median(igds),
                median(feasible), seconds);
    std::fflush(stdout);
  }
  return failures == 0 ? 0 : 1;
}
