#pragma once

#include <pantocat/studies/study_case.h>
#include <pantocat/studies/study_run.h>

#include <vector>

namespace pantocat
{
/**
 * The runs of a study (the Study subsection applied to the case): every
 * method (discretisation x integrator x contact law) runs every refinement (N+1_k, dt_k),
 * coarse to fine; a separate reference run, if asked for, comes last.
 */
class StudyPlan
{
public:
  /// Checks every run's grid against the droppers; throws InputError.
  explicit StudyPlan(const StudyCase& parameters);

  const std::vector<StudyRun>& runs() const { return runs_; }
  unsigned int n_methods() const { return n_methods_; }
  unsigned int n_refinements() const { return n_refinements_; }
  /// Index in runs() of refinement @p k of method @p m.
  unsigned int index(unsigned int m, unsigned int k) const
  {
    return m * n_refinements_ + k;
  }
  /// Index in runs() of the run method @p m is compared with.
  unsigned int reference_index(unsigned int m) const;
  bool separate_reference() const { return separate; }
  /// True if N+1 changes along the refinements (an h-refinement), else only dt does.
  bool refines_space() const;
  /// The largest N+1 of all runs: the wire is sampled on this grid's vertices.
  unsigned int finest_n_intervals() const;

private:
  std::vector<StudyRun> runs_;
  unsigned int n_methods_ = 0, n_refinements_ = 0;
  bool separate = false;
};

/**
 * Observed orders p_k = log(e_{k-1} / e_k) / log(s_{k-1} / s_k) of errors e_k
 * for refinement parameters s_k (h or dt); NaN where an error is zero or not
 * finite. Entry 0 is NaN.
 */
std::vector<double> observed_orders(const std::vector<double>& errors,
                                    const std::vector<double>& parameters);
} // namespace pantocat
