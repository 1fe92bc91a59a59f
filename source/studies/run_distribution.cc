#include <pantocat/studies/run_distribution.h>

#include <deal.II/base/mpi.h>

#include <chrono>
#include <cstring>
#include <deque>
#include <thread>

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

constexpr int tag_result =
    4711;                      ///< rank r -> 0: the run index (-1: ready) and the outcome
constexpr int tag_work = 4712; ///< 0 -> rank r: the next run index (-1: stop)

/// Waits (sleeping, not spinning: the cores belong to the runs) for a message.
MPI_Status wait_for(const int source, const int tag)
{
  MPI_Status status;
  int arrived = 0;
  while (true)
  {
    MPI_Iprobe(source, tag, MPI_COMM_WORLD, &arrived, &status);
    if (arrived)
      return status;
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}

/// Sends run @p k's outcome @p bytes (k = -1: none, the rank is ready) to rank 0.
void send_result(const int k, const std::vector<char>& bytes)
{
  std::vector<char> message(sizeof(int));
  std::memcpy(message.data(), &k, sizeof(int));
  message.insert(message.end(), bytes.begin(), bytes.end());
  MPI_Send(message.data(), static_cast<int>(message.size()), MPI_BYTE, 0, tag_result,
           MPI_COMM_WORLD);
}

/// The work queue's side on rank 0: hands out runs and takes the outcomes in.
class QueueServer
{
public:
  QueueServer(const std::vector<unsigned int>& runs, const unsigned int size,
              const std::function<void(unsigned int, const std::vector<char>&)>& finished)
      : queue(runs.begin(), runs.end()), working(size - 1), finished(finished)
  {
  }
  /// The next run for rank 0 itself; false when the queue is empty.
  bool take(unsigned int& k)
  {
    if (queue.empty())
      return false;
    k = queue.front();
    queue.pop_front();
    return true;
  }
  /// Serves every message that has arrived (or waits for one if @p wait).
  void serve(const bool wait)
  {
    while (working > 0)
    {
      MPI_Status status;
      int arrived = 0;
      if (wait)
        status = wait_for(MPI_ANY_SOURCE, tag_result), arrived = 1;
      else
        MPI_Iprobe(MPI_ANY_SOURCE, tag_result, MPI_COMM_WORLD, &arrived, &status);
      if (!arrived)
        return;
      handle(status);
      if (wait)
        return;
    }
  }
  bool others_working() const { return working > 0; }

private:
  void handle(const MPI_Status& status)
  {
    int count = 0;
    MPI_Get_count(&status, MPI_BYTE, &count);
    std::vector<char> message(count);
    MPI_Recv(message.data(), count, MPI_BYTE, status.MPI_SOURCE, tag_result,
             MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    int k = -1;
    std::memcpy(&k, message.data(), sizeof(int));
    if (k >= 0)
      finished(static_cast<unsigned int>(k),
               std::vector<char>(message.begin() + sizeof(int), message.end()));
    int next = -1;
    if (!queue.empty())
      next = static_cast<int>(queue.front()), queue.pop_front();
    else
      --working;
    MPI_Send(&next, 1, MPI_INT, status.MPI_SOURCE, tag_work, MPI_COMM_WORLD);
  }

  std::deque<unsigned int> queue;
  unsigned int working; ///< ranks other than 0 not yet told to stop
  const std::function<void(unsigned int, const std::vector<char>&)>& finished;
};
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

void RunDistribution::run_queue(
    const std::vector<unsigned int>& runs,
    const std::function<std::vector<char>(unsigned int, const std::function<void()>&)>&
        execute,
    const std::function<void(unsigned int, const std::vector<char>&)>& finished) const
{
  const std::function<void()> nothing = [] {};
  if (size_ == 1)
  {
    for (const unsigned int k : runs)
      finished(k, execute(k, nothing));
    return;
  }
  if (!is_root())
  {
    send_result(-1, {}); // ready
    while (true)
    {
      wait_for(0, tag_work);
      int k = -1;
      MPI_Recv(&k, 1, MPI_INT, 0, tag_work, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      if (k < 0)
        return;
      send_result(k, execute(static_cast<unsigned int>(k), nothing));
    }
  }
  QueueServer server(runs, size_, finished);
  // Every other rank gets its first run (or its stop) before rank 0 takes
  // one: runs shorter than a rank's start-up would otherwise all go to rank 0.
  for (unsigned int r = 1; r < size_; ++r)
    server.serve(true);
  const std::function<void()> poll = [&server] { server.serve(false); };
  unsigned int k = 0;
  while (server.take(k))
  {
    const std::vector<char> outcome = execute(k, poll);
    finished(k, outcome);
    server.serve(false);
  }
  while (server.others_working())
    server.serve(true);
}
} // namespace pantocat
