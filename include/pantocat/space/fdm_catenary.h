#pragma once

#include <pantocat/space/catenary_discretisation.h>

namespace pantocat
{
/**
 * Second-order finite differences of Sec. 4.3 on the equidistant grid
 * x_i = i dx, i = 0..N+1. Unknown i-1 is the displacement at node i
 * (1 <= i <= N); (3) gives q_0 = q_{N+1} = 0 and q''_0 = q''_{N+1} = 0.
 *
 * Integrating (2) over the control volume [x_{i-1/2}, x_{i+1/2}] and using
 * (34) gives M = rho A dx I, D = beta dx I, S = (T/dx) tridiag(-1, 2, -1) and
 * K_w = (EI/dx^3) Q^2 with Q = tridiag(1, -2, 1) (so K_w has 5 on its first
 * and last diagonal entry). A point x belongs to node i when
 * x_{i-1/2} <= x < x_{i+1/2}.
 */
class FdmCatenary : public CatenaryDiscretisation
{
public:
  FdmCatenary(const CatenaryParameters& catenary,
              const DiscretisationParameters& discretisation);

  SpaceMethod method() const override { return SpaceMethod::fdm; }
  bool has_bending_element(Wire) const override { return true; }
  unsigned int n_dofs(Wire) const override { return n_intervals() - 1; }
  void initialize_operator(Wire wire, bool with_bending,
                           BlockOperator& op) const override;
  void add_terms(Wire wire, const WireTerms& terms, BlockOperator& op) const override;
  void interpolate(Wire wire, const std::function<double(double)>& w,
                   const std::function<double(double)>& dw,
                   dealii::Vector<double>& q) const override;
  SparseRow point_row(Wire wire, double x) const override;
  void load_row(double x_c, unsigned int k, SparseRow& row) const override;

  /**
   * The node i with x_{i-1/2} <= x < x_{i+1/2}, robust to round-off: x at a
   * midpoint x_{i-1/2} (up to 1e-9 relative) belongs to node i.
   */
  unsigned int control_volume_node(double x) const;
};
} // namespace pantocat
