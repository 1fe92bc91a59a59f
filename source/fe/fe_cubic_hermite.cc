#include <pantocat/fe/fe_cubic_hermite.h>

#include <deal.II/base/polynomial.h>
#include <deal.II/base/tensor_product_polynomials.h>
#include <deal.II/fe/fe_values.h>

#include <cmath>

namespace pantocat
{
namespace
{
using dealii::Polynomials::Polynomial;

/// The four Hermite polynomials on [0,1] in the dof order of Eq. (27), before
/// the slope scaling by h.
std::vector<Polynomial<double>> reference_hermite_polynomials()
{
  // Coefficients in increasing powers of xi.
  return {Polynomial<double>(std::vector<double>{1., 0., -3., 2.}),  // (1-xi)^2 (1+2xi)
          Polynomial<double>(std::vector<double>{0., 1., -2., 1.}),  // xi (1-xi)^2
          Polynomial<double>(std::vector<double>{0., 0., 3., -2.}),  // xi^2 (3-2xi)
          Polynomial<double>(std::vector<double>{0., 0., -1., 1.})}; // -xi^2 (1-xi)
}

dealii::FiniteElementData<1> hermite_fe_data()
{
  return dealii::FiniteElementData<1>({2, 0}, 1, 3, dealii::FiniteElementData<1>::H2);
}
} // namespace

FE_CubicHermite::FE_CubicHermite()
    : dealii::FE_Poly<1, 1>(
          dealii::TensorProductPolynomials<1>(reference_hermite_polynomials()),
          hermite_fe_data(), std::vector<bool>(4, false),
          std::vector<dealii::ComponentMask>(4, dealii::ComponentMask(1, true)))
{
}

std::string FE_CubicHermite::get_name() const
{
  return "FE_CubicHermite<1>";
}

std::unique_ptr<dealii::FiniteElement<1, 1>> FE_CubicHermite::clone() const
{
  return std::make_unique<FE_CubicHermite>(*this);
}

double FE_CubicHermite::shape_value_on_cell(const unsigned int i, const double xi,
                                            const double h) const
{
  return shape_derivative_on_cell(i, 0, xi, h);
}

double FE_CubicHermite::shape_derivative_on_cell(const unsigned int i,
                                                 const unsigned int k, const double xi,
                                                 const double h) const
{
  // The polynomials of reference_hermite_polynomials(), coefficients in
  // increasing powers of xi; evaluated here without allocation (hot path of
  // the moving contact row).
  static constexpr double coefficients[4][4] = {
      {1., 0., -3., 2.}, {0., 1., -2., 1.}, {0., 0., 3., -2.}, {0., 0., -1., 1.}};
  const double* c = coefficients[i];
  double d = 0.;
  switch (k)
  {
  case 0:
    d = c[0] + xi * (c[1] + xi * (c[2] + xi * c[3]));
    break;
  case 1:
    d = c[1] + xi * (2. * c[2] + xi * 3. * c[3]);
    break;
  case 2:
    d = 2. * c[2] + 6. * c[3] * xi;
    break;
  case 3:
    d = 6. * c[3];
    break;
  default:
    return 0.;
  }
  // d^k/dx^k = h^{-k} d^k/dxi^k; slope functions carry an extra factor h.
  double scale = is_slope_dof(i) ? h : 1.;
  for (unsigned int p = 0; p < k; ++p)
    scale /= h;
  return d * scale;
}

void FE_CubicHermite::fill_fe_values(
    const dealii::Triangulation<1, 1>::cell_iterator& cell,
    const dealii::CellSimilarity::Similarity /*cell_similarity*/,
    const dealii::Quadrature<1>& quadrature, const dealii::Mapping<1, 1>& mapping,
    const dealii::Mapping<1, 1>::InternalDataBase& mapping_internal,
    const dealii::internal::FEValuesImplementation::MappingRelatedData<1, 1>&
        mapping_data,
    const dealii::FiniteElement<1, 1>::InternalDataBase& fe_internal,
    dealii::internal::FEValuesImplementation::FiniteElementRelatedData<1, 1>& output_data)
    const
{
  // Recompute the mapped derivatives on every cell: they are rescaled below,
  // so the "translation" shortcut of FE_Poly would rescale them twice.
  dealii::FE_Poly<1, 1>::fill_fe_values(cell, dealii::CellSimilarity::none, quadrature,
                                        mapping, mapping_internal, mapping_data,
                                        fe_internal, output_data);

  const double h = cell->vertex(1)[0] - cell->vertex(0)[0];
  const dealii::UpdateFlags flags = fe_internal.update_each;
  const unsigned int n_q = quadrature.size();

  for (unsigned int i = 0; i < 4; ++i)
  {
    // Values are stored once by get_data() (unscaled): set them anew.
    if (flags & dealii::update_values)
      for (unsigned int q = 0; q < n_q; ++q)
        output_data.shape_values(i, q) =
            shape_value_on_cell(i, quadrature.point(q)[0], h);
    if (!is_slope_dof(i))
      continue;
    for (unsigned int q = 0; q < n_q; ++q)
    {
      if (flags & dealii::update_gradients)
        output_data.shape_gradients[i][q] *= h;
      if (flags & dealii::update_hessians)
        output_data.shape_hessians[i][q] *= h;
      if (flags & dealii::update_3rd_derivatives)
        output_data.shape_3rd_derivatives[i][q] *= h;
    }
  }
}
} // namespace pantocat
