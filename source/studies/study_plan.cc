#include <pantocat/base/input_error.h>
#include <pantocat/studies/study_plan.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pantocat
{
StudyPlan::StudyPlan(const StudyCase& p)
{
  const StudyParameters& s = p.study;
  std::vector<unsigned int> n = s.n_intervals;
  std::vector<double> dt = s.time_steps;
  if (n.empty())
    n.push_back(p.discretisation.n_intervals);
  if (dt.empty())
    dt.push_back(p.time_integration.time_step);
  if (s.all_combinations)
  {
    std::vector<unsigned int> n_all;
    std::vector<double> dt_all;
    for (const unsigned int n_k : n)
      for (const double dt_k : dt)
        n_all.push_back(n_k), dt_all.push_back(dt_k);
    n = n_all, dt = dt_all;
  }
  n_refinements_ = std::max(n.size(), dt.size());
  n.resize(n_refinements_, n.back());
  dt.resize(n_refinements_, dt.back());

  std::vector<SpaceMethod> discretisations = s.discretisations;
  std::vector<std::string> integrators = s.integrators;
  if (discretisations.empty())
    discretisations.push_back(p.discretisation.method);
  if (integrators.empty())
    integrators.push_back(p.time_integration.integrator);

  const auto check_grid = [&](const SpaceMethod method, const unsigned int n_intervals)
  {
    DiscretisationParameters d = p.discretisation;
    d.method = method;
    d.n_intervals = n_intervals;
    d.check(p.catenary.length());
  };
  // One empty entry: the case's own contact law.
  std::vector<std::string> laws = s.contact_laws;
  if (laws.empty())
    laws.emplace_back();
  for (const SpaceMethod d : discretisations)
    for (const std::string& i : integrators)
      for (const std::string& law : laws)
      {
        ++n_methods_;
        for (unsigned int k = 0; k < n_refinements_; ++k)
        {
          check_grid(d, n[k]);
          runs_.push_back(StudyRun{d, i, n[k], dt[k], false, law, s.penalty});
        }
      }
  separate = s.reference == StudyReference::separate_run;
  if (separate)
  {
    check_grid(s.reference_discretisation, s.reference_n_intervals);
    runs_.push_back(StudyRun{s.reference_discretisation,
                             s.reference_integrator,
                             s.reference_n_intervals,
                             s.reference_time_step,
                             true,
                             {},
                             {}});
  }
  else
    require(n_refinements_ >= 2, "Study/Number of intervals",
            n_refinements_ == 1 ? std::to_string(n[0]) : "",
            "with Study/Reference = finest run the study needs at least two "
            "refinements (the last one is the reference)");
}

unsigned int StudyPlan::reference_index(const unsigned int m) const
{
  return separate ? runs_.size() - 1 : index(m, n_refinements_ - 1);
}

bool StudyPlan::refines_space() const
{
  return runs_[0].n_intervals != runs_[n_refinements_ - 1].n_intervals;
}

unsigned int StudyPlan::finest_n_intervals() const
{
  unsigned int n = 0;
  for (const auto& r : runs_)
    n = std::max(n, r.n_intervals);
  return n;
}

std::vector<double> observed_orders(const std::vector<double>& e,
                                    const std::vector<double>& s)
{
  std::vector<double> orders(e.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 1; k < e.size(); ++k)
    if (e[k] > 0. && e[k - 1] > 0. && std::isfinite(e[k]) && std::isfinite(e[k - 1]) &&
        s[k] != s[k - 1])
      orders[k] = std::log(e[k - 1] / e[k]) / std::log(s[k - 1] / s[k]);
  return orders;
}
} // namespace pantocat
