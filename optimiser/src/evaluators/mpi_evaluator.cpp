// MPI evaluator and worker loop (see the header). Without MPI in the build the functions
// report that MPI is unavailable.
#include "stride/optimiser/nsga2/mpi_evaluator.hpp"

#include <string>
#include <vector>

#ifdef STRIDE_HAVE_MPI
#include <mpi.h>
#endif

namespace stride::opt {

#ifdef STRIDE_HAVE_MPI

namespace {

constexpr int kTagTask = 1;
constexpr int kTagResult = 2;
constexpr int kTagStop = 3;
constexpr int kTagReason = 4;

// A task: index, draw, real count, reals, bits (the draw is exact below 2^53).
std::vector<double> encode_task(std::size_t index, const Candidate& candidate) {
  const Genome& genome = candidate.genome;
  std::vector<double> msg;
  msg.reserve(3 + genome.reals.size() + genome.bits.size());
  msg.push_back(static_cast<double>(index));
  msg.push_back(static_cast<double>(candidate.draw));
  msg.push_back(static_cast<double>(genome.reals.size()));
  msg.insert(msg.end(), genome.reals.begin(), genome.reals.end());
  for (std::uint8_t b : genome.bits) msg.push_back(b);
  return msg;
}

std::vector<double> receive_doubles(int source, int tag, MPI_Status& status) {
  MPI_Probe(source, tag, MPI_COMM_WORLD, &status);
  int count = 0;
  MPI_Get_count(&status, MPI_DOUBLE, &count);
  std::vector<double> msg(static_cast<std::size_t>(count));
  MPI_Recv(msg.data(), count, MPI_DOUBLE, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
           MPI_STATUS_IGNORE);
  return msg;
}

std::string receive_text(int source, int tag) {
  MPI_Status status;
  MPI_Probe(source, tag, MPI_COMM_WORLD, &status);
  int count = 0;
  MPI_Get_count(&status, MPI_CHAR, &count);
  std::string text(static_cast<std::size_t>(count), '\0');
  MPI_Recv(text.data(), count, MPI_CHAR, source, tag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return text;
}

}  // namespace

bool mpi_available() {
  return true;
}

MpiSession::MpiSession(int* argc, char*** argv) {
  MPI_Init(argc, argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
}

void MpiSession::stop_workers() {
  if (stopped_ || rank_ != 0) return;
  stopped_ = true;
  for (int r = 1; r < size_; ++r) MPI_Send(nullptr, 0, MPI_DOUBLE, r, kTagStop, MPI_COMM_WORLD);
}

MpiSession::~MpiSession() {
  stop_workers();
  MPI_Finalize();
}

void MpiEvaluator::evaluate(const Problem& problem, const std::vector<Candidate>& batch,
                            const ReportFn& report) {
  if (ranks_ <= 1) {
    SerialEvaluator().evaluate(problem, batch, report);
    return;
  }
  std::size_t next = 0, outstanding = 0;
  for (int r = 1; r < ranks_ && next < batch.size(); ++r, ++next, ++outstanding) {
    const std::vector<double> msg = encode_task(next, batch[next]);
    MPI_Send(msg.data(), static_cast<int>(msg.size()), MPI_DOUBLE, r, kTagTask, MPI_COMM_WORLD);
  }
  while (outstanding > 0) {
    MPI_Status status;
    const std::vector<double> msg = receive_doubles(MPI_ANY_SOURCE, kTagResult, status);
    const int worker = status.MPI_SOURCE;
    std::string reason = receive_text(worker, kTagReason);
    --outstanding;
    if (next < batch.size()) {
      const std::vector<double> task = encode_task(next, batch[next]);
      MPI_Send(task.data(), static_cast<int>(task.size()), MPI_DOUBLE, worker, kTagTask,
               MPI_COMM_WORLD);
      ++next;
      ++outstanding;
    }
    if (msg.size() < 4) {
      continue;  // malformed: cannot happen between Stride ranks
    }
    const auto index = static_cast<std::size_t>(msg[0]);
    EvaluationOutcome outcome;
    outcome.failed = msg[1] != 0.0;
    const auto objectives = static_cast<std::size_t>(msg[2]);
    const auto constraints = static_cast<std::size_t>(msg[3]);
    if (msg.size() != 4 + objectives + constraints) {
      report(index, EvaluationOutcome::failure("MPI: malformed result from rank " +
                                               std::to_string(worker)));
      continue;
    }
    outcome.objectives.assign(msg.begin() + 4,
                              msg.begin() + 4 + static_cast<std::ptrdiff_t>(objectives));
    outcome.constraints.assign(msg.begin() + 4 + static_cast<std::ptrdiff_t>(objectives),
                               msg.end());
    outcome.reason = std::move(reason);
    report(index, std::move(outcome));
  }
}

Status run_mpi_worker(const Problem& problem) {
  const std::size_t n_reals = problem.shape().reals.size();
  for (;;) {
    MPI_Status status;
    MPI_Probe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
    if (status.MPI_TAG == kTagStop) {
      MPI_Recv(nullptr, 0, MPI_DOUBLE, 0, kTagStop, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      return {};
    }
    const std::vector<double> msg = receive_doubles(0, kTagTask, status);
    if (msg.size() < 3) return Status::error("MPI: malformed task from rank 0");
    Genome genome;
    const auto draw = static_cast<std::uint64_t>(msg[1]);
    const auto reals = static_cast<std::size_t>(msg[2]);
    if (reals != n_reals || msg.size() < 3 + reals)
      return Status::error("MPI: task gene count differs from the problem");
    genome.reals.assign(msg.begin() + 3, msg.begin() + 3 + static_cast<std::ptrdiff_t>(reals));
    for (std::size_t i = 3 + reals; i < msg.size(); ++i)
      genome.bits.push_back(msg[i] != 0.0 ? 1 : 0);
    const EvaluationOutcome outcome = evaluate_safely(problem, genome, draw);
    std::vector<double> out = {msg[0], outcome.failed ? 1.0 : 0.0,
                               static_cast<double>(outcome.objectives.size()),
                               static_cast<double>(outcome.constraints.size())};
    out.insert(out.end(), outcome.objectives.begin(), outcome.objectives.end());
    out.insert(out.end(), outcome.constraints.begin(), outcome.constraints.end());
    MPI_Send(out.data(), static_cast<int>(out.size()), MPI_DOUBLE, 0, kTagResult, MPI_COMM_WORLD);
    MPI_Send(outcome.reason.data(), static_cast<int>(outcome.reason.size()), MPI_CHAR, 0,
             kTagReason, MPI_COMM_WORLD);
  }
}

#else

bool mpi_available() {
  return false;
}
MpiSession::MpiSession(int*, char***) {}
MpiSession::~MpiSession() = default;
void MpiSession::stop_workers() {}
void MpiEvaluator::evaluate(const Problem& problem, const std::vector<Candidate>& batch,
                            const ReportFn& report) {
  SerialEvaluator().evaluate(problem, batch, report);
}
Status run_mpi_worker(const Problem&) {
  return Status::error("this build has no MPI");
}

#endif

}  // namespace stride::opt
