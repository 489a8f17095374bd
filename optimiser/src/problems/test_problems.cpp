// ZDT, DTLZ and constrained test problems with their true fronts.
#include "stride/optimiser/problems/test_problems.hpp"

#include <cmath>
#include <functional>
#include <mutex>
#include <numbers>

#include "stride/optimiser/nsga2/indicators.hpp"

namespace stride::opt {
namespace {

constexpr double kPi = std::numbers::pi;

using EvalFn = std::function<EvaluationOutcome(const std::vector<double>&)>;
using FrontFn = std::function<Points()>;  // dense feasible candidates on the true front

class TestProblem final : public Problem {
 public:
  TestProblem(std::string name, ProblemShape shape, EvalFn eval, FrontFn front,
              std::optional<double> analytic_hv = std::nullopt)
      : name_(std::move(name)),
        shape_(std::move(shape)),
        eval_(std::move(eval)),
        front_(std::move(front)),
        analytic_hv_(analytic_hv) {}

  std::string name() const override { return name_; }
  const ProblemShape& shape() const override { return shape_; }
  EvaluationOutcome evaluate(const Genome& genome) const override { return eval_(genome.reals); }

  std::optional<FrontReference> reference() const override {
    std::call_once(reference_once_, [this] { reference_ = compute_reference(); });
    return reference_;
  }

 private:
  FrontReference compute_reference() const {
    const Points dense = non_dominated(front_());
    FrontReference ref;
    const auto m = static_cast<std::size_t>(shape_.objectives);
    ref.ideal.assign(m, INFINITY);
    ref.nadir.assign(m, -INFINITY);
    for (const auto& p : dense) {
      for (std::size_t k = 0; k < m; ++k) {
        ref.ideal[k] = std::min(ref.ideal[k], p[k]);
        ref.nadir[k] = std::max(ref.nadir[k], p[k]);
      }
    }
    const std::size_t stride = std::max<std::size_t>(1, dense.size() / 1000);
    for (std::size_t i = 0; i < dense.size(); i += stride) ref.front.push_back(dense[i]);
    if (analytic_hv_) {
      ref.true_hypervolume = analytic_hv_;
    } else {
      ref.true_hypervolume =
          hypervolume(normalise(dense, ref.ideal, ref.nadir), std::vector<double>(m, 1.1));
    }
    return ref;
  }

  std::string name_;
  ProblemShape shape_;
  EvalFn eval_;
  FrontFn front_;
  std::optional<double> analytic_hv_;
  mutable std::once_flag reference_once_;
  mutable FrontReference reference_;
};

ProblemShape box(int n, double lo, double hi, int objectives, int constraints) {
  ProblemShape s;
  s.reals.assign(static_cast<std::size_t>(n), RealLimits{lo, hi});
  s.objectives = objectives;
  s.constraints = constraints;
  return s;
}

EvaluationOutcome two(double f1, double f2, std::vector<double> g = {}) {
  EvaluationOutcome o;
  o.objectives = {f1, f2};
  o.constraints = std::move(g);
  return o;
}

/// f2 = curve(f1) sampled at `count` values of f1 in [lo, hi].
Points curve(double lo, double hi, int count, const std::function<double(double)>& f2) {
  Points pts;
  for (int i = 0; i < count; ++i) {
    const double f1 = lo + (hi - lo) * i / (count - 1);
    pts.push_back({f1, f2(f1)});
  }
  return pts;
}

double zdt_g_sum(const std::vector<double>& x) {
  double sum = 0;
  for (std::size_t i = 1; i < x.size(); ++i) sum += x[i];
  return 1.0 + 9.0 * sum / static_cast<double>(x.size() - 1);
}

constexpr int kDense = 10001;

std::unique_ptr<Problem> zdt(int which) {
  const std::string name = "zdt" + std::to_string(which);
  switch (which) {
    case 1:
      return std::make_unique<TestProblem>(
          name, box(30, 0, 1, 2, 0),
          [](const std::vector<double>& x) {
            const double g = zdt_g_sum(x);
            return two(x[0], g * (1 - std::sqrt(x[0] / g)));
          },
          [] { return curve(0, 1, kDense, [](double f) { return 1 - std::sqrt(f); }); });
    case 2:
      return std::make_unique<TestProblem>(
          name, box(30, 0, 1, 2, 0),
          [](const std::vector<double>& x) {
            const double g = zdt_g_sum(x);
            return two(x[0], g * (1 - (x[0] / g) * (x[0] / g)));
          },
          [] { return curve(0, 1, kDense, [](double f) { return 1 - f * f; }); });
    case 3:
      return std::make_unique<TestProblem>(
          name, box(30, 0, 1, 2, 0),
          [](const std::vector<double>& x) {
            const double g = zdt_g_sum(x);
            const double r = x[0] / g;
            return two(x[0], g * (1 - std::sqrt(r) - r * std::sin(10 * kPi * x[0])));
          },
          [] {
            return curve(0, 1, 20001,
                         [](double f) { return 1 - std::sqrt(f) - f * std::sin(10 * kPi * f); });
          });
    case 4: {
      ProblemShape s = box(10, -5, 5, 2, 0);
      s.reals[0] = RealLimits{0, 1};
      return std::make_unique<TestProblem>(
          name, s,
          [](const std::vector<double>& x) {
            double g = 1.0 + 10.0 * static_cast<double>(x.size() - 1);
            for (std::size_t i = 1; i < x.size(); ++i) {
              g += x[i] * x[i] - 10.0 * std::cos(4 * kPi * x[i]);
            }
            return two(x[0], g * (1 - std::sqrt(x[0] / g)));
          },
          [] { return curve(0, 1, kDense, [](double f) { return 1 - std::sqrt(f); }); });
    }
    case 6: {
      // f1's minimum over x1 in [0, 1] is at x1 = 0.0816..., f1 = 0.2807753191.
      return std::make_unique<TestProblem>(
          name, box(10, 0, 1, 2, 0),
          [](const std::vector<double>& x) {
            const double f1 = 1 - std::exp(-4 * x[0]) * std::pow(std::sin(6 * kPi * x[0]), 6);
            double sum = 0;
            for (std::size_t i = 1; i < x.size(); ++i) sum += x[i];
            const double g = 1 + 9 * std::pow(sum / 9.0, 0.25);
            return two(f1, g * (1 - (f1 / g) * (f1 / g)));
          },
          [] { return curve(0.2807753191, 1, kDense, [](double f) { return 1 - f * f; }); });
    }
    default:
      return nullptr;
  }
}

/// Points on the simplex sum = 1 (3 objectives), `divisions` steps per edge.
Points simplex(int divisions) {
  Points pts;
  for (int i = 0; i <= divisions; ++i) {
    for (int j = 0; j <= divisions - i; ++j) {
      const double a = static_cast<double>(i) / divisions;
      const double b = static_cast<double>(j) / divisions;
      pts.push_back({a, b, 1.0 - a - b});
    }
  }
  return pts;
}

std::unique_ptr<Problem> dtlz(int which) {
  if (which == 1) {
    // k = 5: 7 variables. Front: sum f = 0.5; normalised it is the unit simplex, whose
    // dominated volume inside [0, 1.1]^3 is 1.1^3 - 1/6.
    return std::make_unique<TestProblem>(
        "dtlz1", box(7, 0, 1, 3, 0),
        [](const std::vector<double>& x) {
          double g = 0;
          for (std::size_t i = 2; i < x.size(); ++i) {
            g += (x[i] - 0.5) * (x[i] - 0.5) - std::cos(20 * kPi * (x[i] - 0.5));
          }
          g = 100 * (5 + g);
          EvaluationOutcome o;
          o.objectives = {0.5 * x[0] * x[1] * (1 + g), 0.5 * x[0] * (1 - x[1]) * (1 + g),
                          0.5 * (1 - x[0]) * (1 + g)};
          return o;
        },
        [] {
          Points pts = simplex(60);
          for (auto& p : pts) {
            for (double& v : p) v *= 0.5;
          }
          return pts;
        },
        1.331 - 1.0 / 6.0);
  }
  if (which == 2) {
    // k = 10: 12 variables. Front: the unit sphere's positive octant; dominated volume inside
    // [0, 1.1]^3 is 1.1^3 - pi/6.
    return std::make_unique<TestProblem>(
        "dtlz2", box(12, 0, 1, 3, 0),
        [](const std::vector<double>& x) {
          double g = 0;
          for (std::size_t i = 2; i < x.size(); ++i) g += (x[i] - 0.5) * (x[i] - 0.5);
          const double a = x[0] * kPi / 2;
          const double b = x[1] * kPi / 2;
          EvaluationOutcome o;
          o.objectives = {(1 + g) * std::cos(a) * std::cos(b), (1 + g) * std::cos(a) * std::sin(b),
                          (1 + g) * std::sin(a)};
          return o;
        },
        [] {
          Points pts = simplex(60);
          for (auto& p : pts) {
            const double r = std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]);
            for (double& v : p) v /= r;
          }
          return pts;
        },
        1.331 - kPi / 6.0);
  }
  return nullptr;
}

EvaluationOutcome bnh(const std::vector<double>& x) {
  return two(4 * x[0] * x[0] + 4 * x[1] * x[1], (x[0] - 5) * (x[0] - 5) + (x[1] - 5) * (x[1] - 5),
             {25 - (x[0] - 5) * (x[0] - 5) - x[1] * x[1],
              (x[0] - 8) * (x[0] - 8) + (x[1] + 3) * (x[1] + 3) - 7.7});
}

EvaluationOutcome srn(const std::vector<double>& x) {
  return two(2 + (x[0] - 2) * (x[0] - 2) + (x[1] - 1) * (x[1] - 1),
             9 * x[0] - (x[1] - 1) * (x[1] - 1),
             {225 - x[0] * x[0] - x[1] * x[1], -10 - x[0] + 3 * x[1]});
}

EvaluationOutcome tnk(const std::vector<double>& x) {
  return two(x[0], x[1],
             {x[0] * x[0] + x[1] * x[1] - 1 - 0.1 * std::cos(16 * std::atan2(x[0], x[1])),
              0.5 - (x[0] - 0.5) * (x[0] - 0.5) - (x[1] - 0.5) * (x[1] - 0.5)});
}

EvaluationOutcome osy(const std::vector<double>& x) {
  auto sq = [](double v) { return v * v; };
  EvaluationOutcome o;
  o.objectives = {-(25 * sq(x[0] - 2) + sq(x[1] - 2) + sq(x[2] - 1) + sq(x[3] - 4) + sq(x[4] - 1)),
                  sq(x[0]) + sq(x[1]) + sq(x[2]) + sq(x[3]) + sq(x[4]) + sq(x[5])};
  o.constraints = {x[0] + x[1] - 2,     6 - x[0] - x[1],         2 - x[1] + x[0],
                   2 - x[0] + 3 * x[1], 4 - sq(x[2] - 3) - x[3], sq(x[4] - 3) + x[5] - 4};
  return o;
}

/// Keeps the points of `xs` that satisfy every constraint (to 1e-9) and returns objectives.
Points feasible_objectives(const Points& xs, EvaluationOutcome (*fn)(const std::vector<double>&)) {
  Points out;
  for (const auto& x : xs) {
    const EvaluationOutcome o = fn(x);
    bool ok = true;
    for (const double g : o.constraints) ok = ok && g >= -1e-9;
    if (ok) out.push_back(o.objectives);
  }
  return out;
}

std::unique_ptr<Problem> constrained(const std::string& name) {
  if (name == "bnh") {
    ProblemShape s = box(2, 0, 5, 2, 2);
    s.reals[1] = RealLimits{0, 3};
    return std::make_unique<TestProblem>(name, s, bnh, [] {
      Points xs;  // x1 = x2 in [0, 3], then x2 = 3 with x1 in [3, 5]
      for (int i = 0; i <= 6000; ++i) xs.push_back({3.0 * i / 6000, 3.0 * i / 6000});
      for (int i = 1; i <= 4000; ++i) xs.push_back({3 + 2.0 * i / 4000, 3});
      return feasible_objectives(xs, bnh);
    });
  }
  if (name == "srn") {
    return std::make_unique<TestProblem>(name, box(2, -20, 20, 2, 2), srn, [] {
      Points xs;  // x1 = -2.5, x2 in [2.5, 14.79]
      for (int i = 0; i <= 10000; ++i) xs.push_back({-2.5, 2.5 + 12.29 * i / 10000});
      return feasible_objectives(xs, srn);
    });
  }
  if (name == "tnk") {
    return std::make_unique<TestProblem>(name, box(2, 0, kPi, 2, 2), tnk, [] {
      Points xs;  // the boundary r^2 = 1 + 0.1 cos(16 t) of the first constraint
      for (int i = 0; i <= 20000; ++i) {
        const double t = kPi / 2 * i / 20000;
        const double r = std::sqrt(1 + 0.1 * std::cos(16 * t));
        xs.push_back({r * std::cos(t), r * std::sin(t)});
      }
      return feasible_objectives(xs, tnk);
    });
  }
  if (name == "osy") {
    ProblemShape s = box(6, 0, 10, 2, 6);
    s.reals[2] = RealLimits{1, 5};
    s.reals[3] = RealLimits{0, 6};
    s.reals[4] = RealLimits{1, 5};
    return std::make_unique<TestProblem>(name, s, osy, [] {
      Points xs;  // the five segments of Deb (2001), table 8.8
      const int n = 2000;
      for (int i = 0; i <= n; ++i) {
        const double t = static_cast<double>(i) / n;
        xs.push_back({5, 1, 1 + 4 * t, 0, 5, 0});
        xs.push_back({5, 1, 1 + 4 * t, 0, 1, 0});
        const double x1 = 4.056 + (5 - 4.056) * t;
        xs.push_back({x1, (x1 - 2) / 3, 1, 0, 1, 0});
        xs.push_back({0, 2, 1 + 2.732 * t, 0, 1, 0});
        xs.push_back({t, 2 - t, 1, 0, 1, 0});
      }
      return feasible_objectives(xs, osy);
    });
  }
  return nullptr;
}

}  // namespace

const std::vector<std::string>& test_problem_names() {
  static const std::vector<std::string> names = {"zdt1",  "zdt2", "zdt3", "zdt4", "zdt6", "dtlz1",
                                                 "dtlz2", "bnh",  "srn",  "tnk",  "osy"};
  return names;
}

std::unique_ptr<Problem> make_test_problem(const std::string& name) {
  if (name.size() == 4 && name.rfind("zdt", 0) == 0) return zdt(name[3] - '0');
  if (name == "dtlz1") return dtlz(1);
  if (name == "dtlz2") return dtlz(2);
  return constrained(name);
}

}  // namespace stride::opt
