// MPI evaluation (`mpirun -n K stride optimise --mpi ...`): rank 0 runs NSGA-II and hands
// genomes one at a time to ranks 1..K-1 (dynamic scheduling: a free rank gets the next
// genome); the workers evaluate and send the outcome back. With K = 1 rank 0 evaluates
// serially. Messages are JSON text (genome: reals + bits; outcome: objectives, constraints,
// failed, reason), so results are bit-identical to a local evaluation (doubles are sent as
// hex floats). Results come back in any order; the optimiser does not depend on it.
// Available when Stride is built with MPI (STRIDE_HAVE_MPI); MPI is linked into the host side
// only, never into the firmware.
#pragma once

#include "stride/core/status.hpp"
#include "stride/optimiser/nsga2/evaluator.hpp"

namespace stride::opt {

/// True when this build has MPI.
bool mpi_available();

/// MPI_Init on construction, MPI_Finalize on destruction (after telling workers to stop).
class MpiSession {
 public:
  MpiSession(int* argc, char*** argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int size() const { return size_; }
  /// Rank 0: tells every worker to leave its loop (called by the destructor too).
  void stop_workers();

 private:
  int rank_ = 0;
  int size_ = 1;
  bool stopped_ = false;
};

/// Rank 0's evaluator.
class MpiEvaluator final : public Evaluator {
 public:
  explicit MpiEvaluator(int ranks) : ranks_(ranks) {}
  void evaluate(const Problem& problem, const std::vector<Candidate>& batch,
                const ReportFn& report) override;

 private:
  int ranks_;
};

/// Ranks 1..K-1: evaluates genomes from rank 0 until told to stop.
Status run_mpi_worker(const Problem& problem);

}  // namespace stride::opt
