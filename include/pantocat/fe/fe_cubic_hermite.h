#pragma once

#include <deal.II/fe/fe_poly.h>

#include <memory>
#include <string>

namespace pantocat
{
/**
 * The C1-conforming cubic Hermite element on a line, as used for the contact
 * wire in Sec. 4.2 of Arnold & Simeon, Eq. (27).
 *
 * Each vertex carries two degrees of freedom: the value w(x_i) and the slope
 * w'(x_i). On a cell [x_i, x_{i+1}] of length h, with xi = (x - x_i)/h, the
 * local shape functions are (dof order: value/slope at x_i, value/slope at
 * x_{i+1})
 *
 *   N_0 = (1-xi)^2 (1+2 xi),  N_1 = h xi (1-xi)^2,
 *   N_2 = xi^2 (3 - 2 xi),    N_3 = -h xi^2 (1-xi).
 *
 * deal.II 9.4 has no such element (FE_DGQHermite is discontinuous and FE_Q(3)
 * is only C0). The reference-cell polynomials are those of the unit interval;
 * the slope functions are multiplied by the cell length h whenever values,
 * gradients, hessians or third derivatives are filled for a real cell, so that
 * a slope dof means dw/dx on every cell and the global function is C1.
 *
 * Works with DoFHandler<1>, FEValues (values, gradients, hessians, third
 * derivatives), AffineConstraints and DataOut. It has no support points:
 * VectorTools::interpolate and VectorTools::project do not apply.
 */
class FE_CubicHermite : public dealii::FE_Poly<1, 1>
{
public:
  FE_CubicHermite();

  std::string get_name() const override;

  std::unique_ptr<dealii::FiniteElement<1, 1>> clone() const override;

  /// True for the slope dofs (local numbers 1 and 3).
  static bool is_slope_dof(const unsigned int local_dof) { return local_dof % 2 == 1; }

  /**
   * Value of local shape function @p i at the real point with reference
   * coordinate @p xi on a cell of length @p h (with the slope scaling).
   */
  double shape_value_on_cell(unsigned int i, double xi, double h) const;

  /// k-th x-derivative (k = 0..3) of local shape function @p i on a cell of length @p h.
  double shape_derivative_on_cell(unsigned int i, unsigned int k, double xi,
                                  double h) const;

  void
  fill_fe_values(const dealii::Triangulation<1, 1>::cell_iterator& cell,
                 const dealii::CellSimilarity::Similarity cell_similarity,
                 const dealii::Quadrature<1>& quadrature,
                 const dealii::Mapping<1, 1>& mapping,
                 const dealii::Mapping<1, 1>::InternalDataBase& mapping_internal,
                 const dealii::internal::FEValuesImplementation::MappingRelatedData<1, 1>&
                     mapping_data,
                 const dealii::FiniteElement<1, 1>::InternalDataBase& fe_internal,
                 dealii::internal::FEValuesImplementation::FiniteElementRelatedData<1, 1>&
                     output_data) const override;
};
} // namespace pantocat
