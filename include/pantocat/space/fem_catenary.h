#pragma once

#include <pantocat/fe/fe_cubic_hermite.h>
#include <pantocat/space/catenary_discretisation.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/grid/tria.h>

#include <vector>

namespace pantocat
{
/**
 * Finite elements of Sec. 4.2 on deal.II: the carrier with linear Lagrange
 * elements FE_Q<1>(1), the contact wire with C1 cubic Hermite elements
 * (FE_CubicHermite, Eq. (27)), both on one equidistant Triangulation<1> of
 * N+1 cells. The weak form (16)/(17) gives consistent mass, damping, tension
 * and bending matrices (QGauss(4): exact for the cubic x cubic products).
 *
 * Boundary conditions (3): the values at x = 0 and x = L are eliminated; the
 * slopes of the contact wire stay free (w'' = 0 is natural), so the wire has
 * 2N+2 unknowns and the carrier N.
 *
 * Point rows (droppers) evaluate the shape functions at the true position, so
 * droppers need not sit on vertices. The contact row (33) is integrated by
 * Gauss quadrature on the pieces of each cell cut at x_c and x_c +- eps, where
 * the integrand is a polynomial: the result is exact.
 */
class FemCatenary : public CatenaryDiscretisation
{
public:
  FemCatenary(const CatenaryParameters& catenary,
              const DiscretisationParameters& discretisation);

  SpaceMethod method() const override { return SpaceMethod::fem; }
  bool has_bending_element(Wire wire) const override
  {
    return wire == Wire::contact_wire ||
           discretisation.carrier_element == CarrierElement::cubic_hermite;
  }
  unsigned int n_dofs(Wire wire) const override;
  void initialize_operator(Wire wire, bool with_bending,
                           BlockOperator& op) const override;
  void add_terms(Wire wire, const WireTerms& terms, BlockOperator& op) const override;
  void interpolate(Wire wire, const std::function<double(double)>& w,
                   const std::function<double(double)>& dw,
                   dealii::Vector<double>& q) const override;
  SparseRow point_row(Wire wire, double x) const override;
  void load_row(double x_c, unsigned int k, SparseRow& row) const override;
  /// The rows from one pass over the quadrature points (1 to 3 rows).
  void load_rows(double x_c, unsigned int first_k, unsigned int count,
                 SparseRow* const* rows) const override;

  const dealii::DoFHandler<1>& dof_handler(Wire wire) const;
  /// Global dof number -> free unknown, or numbers::invalid_unsigned_int for eliminated
  /// dofs.
  const std::vector<unsigned int>& free_index(Wire wire) const;

  /**
   * The contact-load row (33) over all dofs of the contact wire, including
   * those that (3) eliminates: r_k(i) = int delta^{(k)}(x - x_c) v_i dx.
   */
  void full_load_row(double x_c, unsigned int k, SparseRow& row) const;
  /// full_load_row() for k = @p first_k .. first_k + count - 1 (1 to 3 rows),
  /// each shape value computed once for all.
  void full_load_rows(double x_c, unsigned int first_k, unsigned int count,
                      SparseRow* rows) const;

private:
  struct WireSpace
  {
    dealii::DoFHandler<1> dofs;
    std::vector<std::vector<dealii::types::global_dof_index>>
        cell_dofs; ///< by cell index
    std::vector<unsigned int> free;
    unsigned int n_free = 0;
  };

  /// Index of the cell containing x (the right one at an interior vertex).
  unsigned int cell_index(double x) const;
  /// Value of local shape function i (or its k-th x-derivative) on cell @p c at x.
  double shape(Wire wire, unsigned int c, unsigned int i, unsigned int k, double x) const;
  const std::vector<dealii::types::global_dof_index>& local_dofs(Wire wire,
                                                                 unsigned int c) const;
  const WireSpace& space(Wire wire) const;
  /// The entries of full_load_rows(), in its order: sink(r, dof, value).
  template <typename Sink>
  void for_each_load_entry(double x_c, unsigned int first_k, unsigned int count,
                           Sink&& sink) const;

  dealii::QGauss<1> gauss{4}; ///< degree 3 + 3 = 6 <= 7: exact on each piece of (33)
  dealii::Triangulation<1> triangulation;
  std::vector<dealii::Triangulation<1>::active_cell_iterator> cells; ///< ordered by x
  /// x of the cells' left ends in order, then the last cell's right end: the
  /// moving contact's rows look cells up every step (no cell accessors).
  std::vector<double> cell_start;
  dealii::FE_Q<1> carrier_fe;
  FE_CubicHermite wire_fe;
  WireSpace carrier_space;
  WireSpace wire_space;
};
} // namespace pantocat
