// Benchmark problems with known Pareto fronts, for testing and measuring the optimiser:
//   zdt1 zdt2 zdt3 (30 reals), zdt4 zdt6 (10 reals)            Zitzler, Deb, Thiele 2000
//   dtlz1 (7 reals), dtlz2 (12 reals), three objectives          Deb, Thiele, Laumanns, Zitzler
//   bnh, srn, tnk (2 reals, 2 constraints), osy (6 reals, 6)    constrained, Deb 2001 ch. 8
// Constraints follow Stride's convention g >= 0 satisfied. reference() describes the true front
// (ideal and nadir points, a sample of about 1,000 points for IGD, and the exact normalised
// hypervolume with reference point 1.1: analytic for DTLZ, from a dense sample for the others).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "stride/optimiser/nsga2/problem.hpp"

namespace stride::opt {

/// Names accepted by make_test_problem().
const std::vector<std::string>& test_problem_names();
/// The named problem, or nullptr for an unknown name.
std::unique_ptr<Problem> make_test_problem(const std::string& name);

}  // namespace stride::opt
