#include <pantocat/base/input_error.h>
#include <pantocat/scene/steady_arms.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/studies/packed_bytes.h>
#include <pantocat/studies/sweep_run.h>

#include <chrono>
#include <cstdint>
#include <cstring>
#include <ctime>
#include <memory>
#include <random>

namespace pantocat
{
namespace
{
using packed::get;
using packed::put;

void put_figures(std::vector<char>& b, const ForceFigures& f)
{
  for (const double x : {f.mean, f.std, f.max, f.min, f.mean_plus_3std, f.mean_minus_3std,
                         f.contact_loss_percent})
    put(b, x);
  put(b, static_cast<std::uint64_t>(f.n_points));
}

ForceFigures get_figures(const std::vector<char>& b, std::size_t& pos)
{
  ForceFigures f;
  for (double* x : {&f.mean, &f.std, &f.max, &f.min, &f.mean_plus_3std,
                    &f.mean_minus_3std, &f.contact_loss_percent})
    *x = get<double>(b, pos);
  f.n_points = get<std::uint64_t>(b, pos);
  return f;
}

/// Calls a function every @p interval time points (rank 0 serves its queue from it).
class PollingObserver : public SimulationObserver
{
public:
  PollingObserver(const std::function<void()>& poll, const unsigned int interval)
      : poll(poll), interval(interval)
  {
  }
  void observe(const TimePoint&) override
  {
    if (++points % interval == 0)
      poll();
  }
  bool checkpointed() const override { return false; }

private:
  const std::function<void()>& poll;
  unsigned int interval;
  unsigned long points = 0;
};

/// The figures of every pantograph in contact, from its statistics observer.
std::vector<PantographFigures>
collect_figures(const std::vector<std::unique_ptr<ContactStatistics>>& contacts)
{
  std::vector<PantographFigures> figures;
  for (unsigned int k = 0; k < contacts.size(); ++k)
    if (contacts[k])
    {
      const ContactForceStatistics& s = contacts[k]->result();
      PantographFigures f;
      f.number = k + 1;
      f.raw = s.raw;
      f.has_filtered = s.filtered.has_value();
      if (s.filtered)
        f.filtered = *s.filtered;
      const std::optional<double> uplift = s.max_steady_arm_uplift();
      f.has_uplift = uplift.has_value();
      f.max_steady_arm_uplift = uplift.value_or(0.);
      figures.push_back(f);
    }
  return figures;
}

/// Integrates @p run and evaluates every pantograph in contact; throws as the runner
/// does.
SweepOutcome integrate(const SweepCase& run, const std::function<void()>& poll)
{
  CaseRunner runner(run.case_data);
  runner.check();
  poll();
  const SimulationLayout& layout = runner.layout();
  std::vector<std::unique_ptr<ContactStatistics>> contacts(layout.pantographs.size());
  PollingObserver polling(poll, 20);
  std::vector<SimulationObserver*> observers{&polling};
  const std::vector<double> arms =
      SteadyArms::positions(runner.case_data().scene, runner.case_data().catenary);
  for (unsigned int k = 0; k < layout.pantographs.size(); ++k)
    if (layout.pantographs[k].has_contact())
      observers.push_back(
          (contacts[k] = std::make_unique<ContactStatistics>(
               run.statistics, runner.discretisation(), runner.system(), arms, k))
              .get());
  SweepOutcome outcome;
  outcome.steps = runner.run(observers).integrator.steps;
  outcome.pantographs = collect_figures(contacts);
  return outcome;
}
} // namespace

const char* to_string(const SweepOutcome::Status status)
{
  return status == SweepOutcome::Status::completed ? "completed"
         : status == SweepOutcome::Status::failed  ? "failed"
                                                   : "refused";
}

std::vector<char> SweepOutcome::pack() const
{
  std::vector<char> b;
  put(b, static_cast<int>(status));
  packed::put_string(b, reason);
  put(b, wall_seconds);
  put(b, cpu_seconds);
  put(b, static_cast<std::uint64_t>(steps));
  put(b, rank);
  put(b, static_cast<std::uint64_t>(pantographs.size()));
  for (const PantographFigures& p : pantographs)
  {
    put(b, p.number);
    put_figures(b, p.raw);
    put(b, static_cast<char>(p.has_filtered));
    put_figures(b, p.filtered);
    put(b, static_cast<char>(p.has_uplift));
    put(b, p.max_steady_arm_uplift);
  }
  return b;
}

SweepOutcome SweepOutcome::unpack(const std::vector<char>& b)
{
  std::size_t pos = 0;
  SweepOutcome o;
  o.status = static_cast<Status>(get<int>(b, pos));
  o.reason = packed::get_string(b, pos);
  o.wall_seconds = get<double>(b, pos);
  o.cpu_seconds = get<double>(b, pos);
  o.steps = get<std::uint64_t>(b, pos);
  o.rank = get<unsigned int>(b, pos);
  o.pantographs.resize(get<std::uint64_t>(b, pos));
  for (PantographFigures& p : o.pantographs)
  {
    p.number = get<unsigned int>(b, pos);
    p.raw = get_figures(b, pos);
    p.has_filtered = get<char>(b, pos) != 0;
    p.filtered = get_figures(b, pos);
    p.has_uplift = get<char>(b, pos) != 0;
    p.max_steady_arm_uplift = get<double>(b, pos);
  }
  return o;
}

SweepOutcome execute_sweep_run(const SweepCase& run, const std::function<void()>& poll)
{
  const auto start = std::chrono::steady_clock::now();
  const std::clock_t cpu_start = std::clock();
  SweepOutcome outcome;
  try
  {
    outcome = integrate(run, poll);
  }
  catch (const InputError& e)
  {
    outcome.status = SweepOutcome::Status::refused;
    outcome.reason = e.what();
  }
  catch (const SimulationError& e)
  {
    outcome.status = SweepOutcome::Status::failed;
    outcome.reason = e.what();
  }
  outcome.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  outcome.cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  return outcome;
}

InstallationDeviations sample_deviations(const SweepParameters& p,
                                         const unsigned int n_droppers,
                                         const unsigned int n_steady_arms,
                                         const unsigned int sample)
{
  std::mt19937_64 generator(p.seed + sample);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  std::normal_distribution<double> normal(0., 1. / 3.);
  // A draw in units of the tolerance: uniform in [-1, 1], or normal with 3 sigma = 1.
  const auto draw = [&]()
  {
    return p.distribution == DeviationDistribution::uniform ? uniform(generator)
                                                            : normal(generator);
  };
  InstallationDeviations d;
  d.dropper_lengths.resize(n_droppers);
  for (double& x : d.dropper_lengths)
    x = p.dropper_length_tolerance * draw();
  d.steady_arm_heights.resize(n_steady_arms);
  for (double& x : d.steady_arm_heights)
    x = p.steady_arm_height_tolerance * draw();
  d.carrier_tension_factor = 1. + p.tension_tolerance * draw();
  d.contact_wire_tension_factor = 1. + p.tension_tolerance * draw();
  return d;
}
} // namespace pantocat
