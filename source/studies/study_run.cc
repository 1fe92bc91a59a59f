#include <pantocat/analysis/eigenfrequency_analysis.h>
#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/simulation/case_runner.h>
#include <pantocat/studies/packed_bytes.h>
#include <pantocat/studies/study_run.h>
#include <pantocat/time/integrator_registry.h>

#include <set>

#include <chrono>
#include <cstring>
#include <ctime>
#include <sstream>

namespace pantocat
{
std::string StudyRun::method() const
{
  return std::string(to_string(discretisation)) + " + " + integrator +
         (contact_law.empty() ? "" : ", " + contact_law + " contact");
}

std::string StudyRun::label() const
{
  std::ostringstream s;
  s << method() << ", N+1 = " << n_intervals << ", dt = " << time_step << " s";
  return s.str();
}

Case StudyRun::parameters(const Case& base) const
{
  Case p = base;
  p.discretisation.method = discretisation;
  p.discretisation.n_intervals = n_intervals;
  p.time_integration.integrator = integrator;
  p.time_integration.time_step = time_step;
  p.time_integration.force_step_size = false;
  if (!contact_law.empty())
    for (PantographCase& pantograph : p.scene.pantographs)
    {
      pantograph.contact = contact_law == "bilateral" ? Constraint::Kind::bilateral
                                                      : Constraint::Kind::unilateral;
      pantograph.contact_compliance = contact_law == "penalty" ? penalty : Compliance{};
    }
  return p;
}

std::string StudyRun::contact_law_in(const Case& base) const
{
  return contact_law.empty() ? base.scene.pantographs[0].contact_law() : contact_law;
}

const char* to_string(const RunOutcome::Status status)
{
  return status == RunOutcome::Status::completed ? "completed"
         : status == RunOutcome::Status::skipped ? "skipped"
                                                 : "failed";
}

namespace
{
using packed::get;
using packed::get_string;
using packed::get_vector;
using packed::put;
using packed::put_string;
using packed::put_vector;

/// Records lambda_p (the contact constraint's multiplier) at every time point.
class ContactForceRecorder : public SimulationObserver
{
public:
  explicit ContactForceRecorder(RunOutcome& outcome) : outcome(outcome) {}
  void start(const SimulationLayout& layout) override
  {
    contact = layout.contacts().at(0)->contact;
  }
  void observe(const TimePoint& p) override
  {
    outcome.t.push_back(p.t);
    outcome.lambda_p.push_back(p.lambda[contact]);
  }

private:
  RunOutcome& outcome;
  unsigned int contact = 0;
};

double cpu_seconds_since(const std::clock_t start)
{
  return static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
}
} // namespace

void RunOutcome::pack(std::vector<char>& b) const
{
  put(b, static_cast<int>(status));
  put_string(b, message);
  put(b, cpu_seconds);
  put(b, static_cast<std::uint64_t>(steps));
  put_vector(b, t);
  put_vector(b, lambda_p);
  put_vector(b, wire);
  put(b, f_min_carrier);
  put(b, f_min_contact_wire);
  contact.pack(b);
}

RunOutcome RunOutcome::unpack(const std::vector<char>& b, std::size_t& pos)
{
  RunOutcome o;
  o.status = static_cast<Status>(get<int>(b, pos));
  o.message = get_string(b, pos);
  o.cpu_seconds = get<double>(b, pos);
  o.steps = get<std::uint64_t>(b, pos);
  o.t = get_vector<double>(b, pos);
  o.lambda_p = get_vector<double>(b, pos);
  o.wire = get_vector<double>(b, pos);
  o.f_min_carrier = get<double>(b, pos);
  o.f_min_contact_wire = get<double>(b, pos);
  o.contact = ContactFigures::unpack(b, pos);
  return o;
}

void check_study_grids(const std::vector<StudyRun>& runs, const Case& base)
{
  std::set<std::pair<std::string, unsigned int>> checked;
  for (const StudyRun& run : runs)
  {
    const Case p = run.parameters(base);
    if (!checked
             .insert({to_string(p.discretisation.method), p.discretisation.n_intervals})
             .second)
      continue;
    try
    {
      // The run's own case: its droppers must find their nodes on this grid.
      const CaseRunner runner(p);
    }
    catch (const InputError& e)
    {
      throw InputError("Study: run " + run.label() + ": " + e.what());
    }
  }
}

RunOutcome execute_study_run(const StudyRun& run, const Case& base,
                             const RunRequest& request)
{
  RunOutcome outcome;
  const Case p = run.parameters(base);
  const std::clock_t start = std::clock();
  CaseRunner runner(p);
  // Above the explicit method's limit (2/omega_max, or with the moving contact
  // the limit of CaseRunner::step_size_problem): skipped and reported.
  if (const std::string problem = runner.step_size_problem(); !problem.empty())
  {
    outcome.status = RunOutcome::Status::skipped;
    outcome.message = "dt = " + number_to_string(run.time_step) + " s is " + problem;
    return outcome;
  }
  ContactForceRecorder recorder(outcome);
  std::vector<SimulationObserver*> observers{&recorder};
  std::optional<ContactFiguresRecorder> contact;
  if (request.contact_statistics)
  {
    contact.emplace(runner, *request.contact_statistics);
    for (SimulationObserver* o : contact->observers())
      observers.push_back(o);
  }
  CaseRunner::Result result;
  try
  {
    result = runner.run(observers);
  }
  catch (const SimulationError& e)
  {
    outcome.status = RunOutcome::Status::failed;
    outcome.message = e.what();
    outcome.cpu_seconds = cpu_seconds_since(start);
    return outcome;
  }
  outcome.cpu_seconds = cpu_seconds_since(start);
  outcome.steps = result.integrator.steps;
  if (contact)
    outcome.contact = contact->figures(result.integrator);

  const double length = p.catenary.length();
  for (unsigned int j = 0; request.wire_samples > 0 && j <= request.wire_samples; ++j)
    outcome.wire.push_back(runner.contact_wire_displacement(
        result.final_state.q, length * j / request.wire_samples));
  if (request.eigenfrequencies)
    for (const auto& f : compute_extreme_frequencies(runner.discretisation()))
      (f.subsystem == "carrier" ? outcome.f_min_carrier : outcome.f_min_contact_wire) =
          f.f_min_hz;
  return outcome;
}
} // namespace pantocat
