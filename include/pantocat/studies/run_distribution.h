#pragma once

#include <pantocat/studies/study_run.h>

#include <functional>
#include <vector>

namespace pantocat
{
/**
 * Spreads the independent runs of a study over the MPI ranks: run k goes to
 * rank k % size, and the outcomes are gathered on rank 0. Without MPI (a
 * serial start, no mpirun) there is one rank and nothing is sent.
 */
class RunDistribution
{
public:
  /// MPI_COMM_WORLD if MPI is initialised, else a single serial rank.
  RunDistribution();

  unsigned int rank() const { return rank_; }
  unsigned int size() const { return size_; }
  bool is_root() const { return rank_ == 0; }
  bool owns(unsigned int k) const { return k % size_ == rank_; }

  /**
   * Runs execute(k) for the k < n_runs this rank owns and returns all n_runs
   * outcomes in order on rank 0 (an empty vector on the other ranks).
   */
  std::vector<RunOutcome>
  run_and_gather(unsigned int n_runs,
                 const std::function<RunOutcome(unsigned int)>& execute) const;

  /**
   * A work queue on rank 0 for runs that differ in length (dynamic load
   * balancing): every rank asks rank 0 for its next run when it is free.
   * Each other rank gets its first run before rank 0 takes one (rank 0 waits
   * for their start-up), so that every rank works when there are as many runs.
   * Rank 0 works too: it takes runs from the queue itself and serves the other
   * ranks' requests whenever @p execute calls the poll function it is given
   * (every few time steps), so that no rank waits long and 2 ranks keep 2
   * cores busy. @p runs are the run indices in the order to hand them out
   * (longest first balances best). On rank 0, @p finished(k, outcome) is
   * called for each run as it ends (in the order they end); the other ranks
   * return when the queue is empty. Waiting ranks sleep instead of spinning.
   * Without MPI (one rank) rank 0 runs them all in order.
   */
  void run_queue(
      const std::vector<unsigned int>& runs,
      const std::function<std::vector<char>(unsigned int, const std::function<void()>&)>&
          execute,
      const std::function<void(unsigned int, const std::vector<char>&)>& finished) const;

private:
  unsigned int rank_ = 0;
  unsigned int size_ = 1;
};
} // namespace pantocat
