#include <pantocat/scene/steady_arms.h>
#include <pantocat/simulation/run_events.h>
#include <pantocat/studies/contact_figures.h>
#include <pantocat/studies/packed_bytes.h>

#include <algorithm>

namespace pantocat
{
using packed::get;
using packed::put;

unsigned long ContactFigures::contact_events() const
{
  return std::count_if(events.begin(), events.end(),
                       [&](const StudyEvent& e) { return e.constraint == contact; });
}

void ContactFigures::pack(std::vector<char>& b) const
{
  for (const double x : {loss_percent, filtered_max, filtered_min, filtered_std,
                         min_unilateral_force, min_unilateral_time})
    put(b, x);
  packed::put_string(b, min_unilateral_constraint);
  put(b, contact);
  put(b, static_cast<std::uint64_t>(events.size()));
  for (const StudyEvent& e : events)
  {
    put(b, e.t);
    put(b, e.constraint);
    put(b, static_cast<char>(e.closes));
  }
}

ContactFigures ContactFigures::unpack(const std::vector<char>& b, std::size_t& pos)
{
  ContactFigures f;
  for (double* x : {&f.loss_percent, &f.filtered_max, &f.filtered_min, &f.filtered_std,
                    &f.min_unilateral_force, &f.min_unilateral_time})
    *x = get<double>(b, pos);
  f.min_unilateral_constraint = packed::get_string(b, pos);
  f.contact = get<unsigned int>(b, pos);
  f.events.resize(get<std::uint64_t>(b, pos));
  for (StudyEvent& e : f.events)
  {
    e.t = get<double>(b, pos);
    e.constraint = get<unsigned int>(b, pos);
    e.closes = get<char>(b, pos) != 0;
  }
  return f;
}

ContactFiguresRecorder::UnilateralMinimum::UnilateralMinimum(
    const SemiDiscreteSystem& system)
{
  for (unsigned int i = 0; i < system.n_constraints(); ++i)
    if (system.constraints[i]->is_unilateral())
      unilateral.push_back(i);
}

void ContactFiguresRecorder::UnilateralMinimum::start(const SimulationLayout& layout)
{
  names = layout.constraint_names;
}

void ContactFiguresRecorder::UnilateralMinimum::observe(const TimePoint& p)
{
  for (const unsigned int i : unilateral)
    if (!(p.lambda[i] >= force)) // the first value, or a smaller one
    {
      force = p.lambda[i];
      constraint = names[i];
      time = p.t;
    }
}

ContactFiguresRecorder::ContactFiguresRecorder(const CaseRunner& runner,
                                               const StatisticsParameters& statistics)
    : layout(runner.layout()),
      contact(
          statistics, runner.discretisation(), runner.system(),
          SteadyArms::positions(runner.case_data().scene, runner.case_data().catenary),
          0),
      minimum(runner.system())
{
}

std::vector<SimulationObserver*> ContactFiguresRecorder::observers()
{
  return {&contact, &log, &minimum};
}

ContactFigures
ContactFiguresRecorder::figures(const IntegratorStatistics& integrator) const
{
  ContactFigures f;
  const ContactForceStatistics& s = contact.result();
  f.loss_percent = s.raw.contact_loss_percent;
  if (s.filtered)
  {
    f.filtered_max = s.filtered->max;
    f.filtered_min = s.filtered->min;
    f.filtered_std = s.filtered->std;
  }
  f.min_unilateral_force = minimum.force;
  f.min_unilateral_constraint = minimum.constraint;
  f.min_unilateral_time = minimum.time;
  f.contact = layout.pantographs.at(0).contact;
  const std::vector<std::string>& names = layout.constraint_names;
  for (const ConstraintEvent& e : run_events(layout, integrator, log))
    f.events.push_back(
        {e.t,
         static_cast<unsigned int>(std::find(names.begin(), names.end(), e.constraint) -
                                   names.begin()),
         closes(e)});
  return f;
}
} // namespace pantocat
