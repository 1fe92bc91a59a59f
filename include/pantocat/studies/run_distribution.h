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

private:
  unsigned int rank_ = 0;
  unsigned int size_ = 1;
};
} // namespace pantocat
