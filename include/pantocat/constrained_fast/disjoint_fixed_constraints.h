#pragma once

#include <pantocat/constrained_fast/mass_inverse.h>
#include <pantocat/lac/sparse_row.h>

#include <vector>

namespace pantocat
{
/**
 * The rigid constraints with constant rows (droppers, carrier supports) of
 * the half-explicit method (39)-(41) when no two of them share an unknown and
 * W = M + dt/2 D and M are diagonal on their unknowns: the FDM's droppers and
 * supports. Then G_F W^-1 G_F^T and G_F M^-1 G_F^T are diagonal, the columns
 * W^-1 G_k^T and M^-1 G_k^T live on G_k's own unknowns, and each
 * constraint's multipliers follow from its own row once the moving
 * constraints' (the contacts') forces are in the state:
 *
 *  - (39): lambda_k = -G_k a / (G_k W^-1 G_k^T), a += W^-1 G_k^T lambda_k, and
 *    the rows of G_k predicted again (v* = v_{n-1} + 2 dt a, q* = q_n + dt
 *    (v_n + v*)/2);
 *  - (40) with G_t = 0: from r_g = -(G_k q* + z_k), r_v = -G_k v*, eta_k =
 *    S_k^-1 r_v / (2 dt), mu_k = S_k^-1 r_g / dt - dt eta_k (S_k = G_k M^-1
 *    G_k^T), q += M^-1 G_k^T (dt^2 eta_k + dt mu_k), v += M^-1 G_k^T 2 dt eta_k;
 *    then the gap g_k at t_{n+1}.
 *
 * One pass over the constraints per level, each touching only its own few
 * unknowns (entries stored side by side: index, G, W^-1 G^T, M^-1 G^T), instead of
 * the Schur-complement path's separate passes (right-hand sides, solves,
 * columns, predictions, gaps). The moving constraints border only the fixed
 * ones on their unknowns (FastHalfExplicitStepSystem solves that small system
 * first, with smoothed_inverse() and mass_inverse() below).
 */
class DisjointFixedConstraints
{
public:
  /**
   * Takes the rows @p rows (offsets @p offsets; constraint numbers @p ids) if
   * they qualify (see the class) for @p W = M + dt/2 D and @p M; otherwise
   * holds nothing and returns false.
   */
  bool initialize(const CompressedRows& rows, const std::vector<double>& offsets,
                  const std::vector<unsigned int>& ids, const MassInverse& W,
                  const MassInverse& M, unsigned int n_dofs);
  /// True after a successful initialize().
  bool used() const { return in_use; }

  /**
   * The constraints k with @p keep[k] carry multipliers in (39), respectively
   * (40); @p version names the selection (the same version, the same keep:
   * nothing to do).
   */
  void select_acceleration(const std::vector<bool>& keep, unsigned long version);
  void select_position(const std::vector<bool>& keep, unsigned long version);
  /// 1/(G_k W^-1 G_k^T) if k is selected for (39), else 0.
  double smoothed_inverse(const unsigned int k) const { return inverse_w[k]; }
  /// 1/(G_k M^-1 G_k^T) if k is selected for (40), else 0.
  double mass_inverse(const unsigned int k) const { return inverse_m[k]; }

  /// What accelerate() predicts from: q_n, v_n, v_{n-1} and the step.
  struct Prediction
  {
    const double *q, *v, *v_previous;
    double *q_new, *v_new;
    double dt;
  };
  /**
   * (39) for the selected constraints: lambda[id_k] = lambda_k, a += W^-1
   * G_k^T lambda_k; with @p predict, q*, v* of their rows from the final a.
   * With @p project_now too, the constraints k with project_now[k] (those no
   * moving constraint borders) are projected at once, as project() does,
   * while their rows are in the cache (one pass for both levels).
   */
  void accelerate(double* a, std::vector<double>& lambda, const Prediction* predict,
                  const std::vector<bool>* project_now = nullptr,
                  std::vector<double>* gaps = nullptr) const;
  /**
   * (40) for the selected constraints on q = q*, v = v* (the moving
   * constraints' corrections already added), then gaps[id_k] = G_k q_{n+1} +
   * z_k for every constraint.
   */
  void project(double* q, double* v, double dt, std::vector<double>& gaps) const;
  /// The same for the constraints @p which only.
  void project(double* q, double* v, double dt, std::vector<double>& gaps,
               const std::vector<unsigned int>& which) const;
  /// accelerate() for the @p count constraints @p which only (in that order).
  void accelerate(const unsigned int* which, unsigned int count, double* a,
                  std::vector<double>& lambda, const Prediction* predict,
                  const std::vector<bool>* project_now = nullptr,
                  std::vector<double>* gaps = nullptr) const;

private:
  /**
   * The constraints with two unknowns each, by field, indexed by constraint
   * (the entries of the others are not used): consecutive constraints'
   * coefficients are consecutive in memory, so that accelerate_and_project()
   * reads them four at a time.
   */
  struct Pairs
  {
    std::vector<unsigned int> j0, j1; ///< the unknowns
    std::vector<double> g0, g1;       ///< G_k there
    std::vector<double> w0, w1;       ///< (W^-1 G_k^T) there
    std::vector<double> m0, m1;       ///< (M^-1 G_k^T) there
  };
  /// accelerate() and project() of the @p count <= batch consecutive constraints
  /// from @p first, each with two unknowns, phase by phase.
  static constexpr unsigned int batch = 16;
  void accelerate_and_project(unsigned int first, unsigned int count, double* a,
                              std::vector<double>& lambda, const Prediction& predict,
                              std::vector<double>& gaps) const;
  /// (40) and the gap for constraint @p k.
  void project_one(unsigned int k, double* q, double* v, double dt,
                   std::vector<double>& gaps) const;
  struct Entry
  {
    unsigned int unknown;
    double g;     ///< G_k at the unknown
    double w_col; ///< (W^-1 G_k^T) there
    double m_col; ///< (M^-1 G_k^T) there
  };
  bool in_use = false;
  std::vector<unsigned int> start{0}; ///< constraint k: entries [start[k], start[k+1])
  std::vector<Entry> entries;
  Pairs pairs;
  std::vector<double> offset;
  std::vector<unsigned int> id;
  std::vector<double> schur_w, schur_m;     ///< G_k W^-1 G_k^T, G_k M^-1 G_k^T
  std::vector<double> inverse_w, inverse_m; ///< their inverses where selected, else 0
  /// The versions of the selections in inverse_w and inverse_m (0: none yet).
  unsigned long selected_w = 0, selected_m = 0;
};
} // namespace pantocat
