#pragma once

#include <pantocat/analysis/elasticity_parameters.h>
#include <pantocat/catenary/catenary_parameters.h>
#include <pantocat/space/catenary_discretisation.h>
#include <pantocat/system/semi_discrete_system.h>

#include <string>
#include <vector>

namespace pantocat
{
/// The figures of the static check for one force (summary.json "elasticity").
struct ElasticityFigures
{
  double force = 0.;      ///< F [N]
  double minimum = 0.;    ///< e_min [mm/N]
  double maximum = 0.;    ///< e_max [mm/N]
  double mean = 0.;       ///< arithmetic mean over the load points [mm/N]
  double uniformity = 0.; ///< (e_max - e_min) / (e_max + e_min)
};

/**
 * e_min, e_max, the mean and the uniformity (e_max - e_min) / (e_max + e_min)
 * of the elasticities @p e [mm/N] under @p force (NaN uniformity if all are 0).
 */
ElasticityFigures elasticity_figures(double force, const std::vector<double>& e);

/**
 * The result of the static check: under each upward force F alone at each
 * load point x_i, the uplift u = w_w(x_i; F) - w_w(x_i; 0) of the contact
 * wire at the load point, and the droppers that slacken.
 */
struct StaticElasticity
{
  unsigned int span = 0;      ///< 1-based
  std::vector<double> x;      ///< the load points [m], along the section
  std::vector<double> forces; ///< F [N]
  /// uplift[f][i]: u [m] under forces[f] at x[i]
  std::vector<std::vector<double>> uplift;
  /// slackened[f][i]: the droppers (1-based numbers of the section) slack under
  /// forces[f] at x[i] that are taut without it
  std::vector<std::vector<std::vector<unsigned int>>> slackened;
  unsigned int solves = 0;                ///< static solves with a load
  unsigned int active_set_iterations = 0; ///< over all of them
  double seconds = 0.;                    ///< wall time: preparation and every solve

  /// e = 1000 u / F [mm/N] of forces[@p f] at every point.
  std::vector<double> elasticity(unsigned int f) const;
  ElasticityFigures figures(unsigned int f) const;
};

/**
 * @p n equally spaced points of span @p span (1-based) of @p catenary, from
 * its first to its second support.
 */
std::vector<double> span_points(const CatenaryParameters& catenary, unsigned int span,
                                unsigned int n);

/**
 * The static check of @p parameters (enabled()) on the catenary @p catenary
 * (a system without pantographs, whose contact wire is discretised by @p
 * space): the static state without load, then for each point and force the
 * static state with the upward point force F H^T (H the row of w_w at the
 * point) added, the droppers (constraints @p dropper_indices) free to slacken
 * as their model says (unilateral, or tension-only springs). K is factorised
 * and G K^-1 G^T formed once for all loads (StaticEquilibriumSolver); each
 * load's active-set iteration starts from the unloaded state's active set.
 * At a section end the pinned wire does not move: u = 0 there, without a solve.
 */
StaticElasticity static_elasticity(const SemiDiscreteSystem& catenary,
                                   const CatenaryDiscretisation& space,
                                   const std::vector<unsigned int>& dropper_indices,
                                   const ElasticityParameters& parameters);
} // namespace pantocat
