#pragma once

#include <pantocat/simulation/case.h>
#include <pantocat/simulation/statistics_parameters.h>
#include <pantocat/studies/study_parameters.h>

#include <string>

namespace pantocat
{
/**
 * What a study runs: a base case, the study's own parameters (subsection
 * Study) and where its tables and plots go. Each run of the study is the base
 * case with its discretisation, grid, integrator and step replaced, run by
 * the CaseRunner.
 */
struct StudyCase : Case
{
  StudyParameters study;
  /// The window and low pass of Study/Quantities = contact statistics.
  StatisticsParameters statistics;
  struct Output
  {
    std::string directory = "output";
    bool plots = true;
  } output;
};
} // namespace pantocat
