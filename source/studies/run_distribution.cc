#include <pantocat/studies/run_distribution.h>

#include <deal.II/base/mpi.h>

namespace pantocat
{
namespace
{
/// A run that throws becomes a failed outcome: the other ranks must not wait for it.
RunOutcome guarded(const std::function<RunOutcome(unsigned int)>& execute,
                   const unsigned int k)
{
  try
  {
    return execute(k);
  }
  catch (const std::exception& e)
  {
    RunOutcome failed;
    failed.status = RunOutcome::Status::failed;
    failed.message = e.what();
    return failed;
  }
}
} // namespace

RunDistribution::RunDistribution()
{
  if (dealii::Utilities::MPI::job_supports_mpi())
  {
    rank_ = dealii::Utilities::MPI::this_mpi_process(MPI_COMM_WORLD);
    size_ = dealii::Utilities::MPI::n_mpi_processes(MPI_COMM_WORLD);
  }
}

std::vector<RunOutcome> RunDistribution::run_and_gather(
    const unsigned int n_runs,
    const std::function<RunOutcome(unsigned int)>& execute) const
{
  std::vector<RunOutcome> all(n_runs);
  if (size_ == 1)
  {
    for (unsigned int k = 0; k < n_runs; ++k)
      all[k] = guarded(execute, k);
    return all;
  }
  // Each rank packs its outcomes in the order k = rank, rank + size, ...
  std::vector<char> local;
  for (unsigned int k = rank_; k < n_runs; k += size_)
    guarded(execute, k).pack(local);
  const std::vector<std::vector<char>> gathered =
      dealii::Utilities::MPI::gather(MPI_COMM_WORLD, local, 0);
  if (!is_root())
    return {};
  for (unsigned int r = 0; r < size_; ++r)
  {
    std::size_t position = 0;
    for (unsigned int k = r; k < n_runs; k += size_)
      all[k] = RunOutcome::unpack(gathered[r], position);
  }
  return all;
}
} // namespace pantocat
