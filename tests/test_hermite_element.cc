// The C1 cubic Hermite element (27) on deal.II: partition of unity, exact
// reproduction of cubics on a non-uniform mesh, C1 continuity across
// vertices, and use with AffineConstraints and DataOut.
#include <pantocat/fe/fe_cubic_hermite.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/data_out.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <sstream>

using namespace dealii;
using pantocat::FE_CubicHermite;

namespace
{
/// A non-uniform mesh of [0, 3] with cells of lengths 0.5, 1.0, 0.25, 1.25.
void make_nonuniform_mesh(Triangulation<1>& tria)
{
  const std::vector<std::vector<double>> step_sizes = {{0.5, 1.0, 0.25, 1.25}};
  GridGenerator::subdivided_hyper_rectangle(tria, step_sizes, Point<1>(0.), Point<1>(3.));
}

double cubic(double x)
{
  return 0.3 - 1.2 * x + 0.7 * x * x - 0.4 * x * x * x;
}
double cubic_d1(double x)
{
  return -1.2 + 1.4 * x - 1.2 * x * x;
}
double cubic_d2(double x)
{
  return 1.4 - 2.4 * x;
}

/// Nodal interpolation: value and slope of f at every vertex.
Vector<double> hermite_interpolant(const DoFHandler<1>& dofs, double (*f)(double),
                                   double (*df)(double))
{
  Vector<double> u(dofs.n_dofs());
  for (const auto& cell : dofs.active_cell_iterators())
    for (unsigned int v = 0; v < 2; ++v)
    {
      const double x = cell->vertex(v)[0];
      u(cell->vertex_dof_index(v, 0)) = f(x);
      u(cell->vertex_dof_index(v, 1)) = df(x);
    }
  return u;
}
} // namespace

TEST(HermiteElement, PartitionOfUnityOnTheReferenceCell)
{
  // N_0 + N_2 = 1 and the slope functions carry no constant: machine precision.
  const FE_CubicHermite fe;
  for (const double h : {0.04, 1.0, 3.7})
    for (double xi = 0.; xi <= 1.; xi += 0.0625)
    {
      EXPECT_NEAR(fe.shape_value_on_cell(0, xi, h) + fe.shape_value_on_cell(2, xi, h), 1.,
                  1e-15);
      EXPECT_NEAR(fe.shape_derivative_on_cell(0, 1, xi, h) +
                      fe.shape_derivative_on_cell(2, 1, xi, h),
                  0., 1e-13 / h);
    }
}

TEST(HermiteElement, DofsAreValuesAndSlopesAtVertices)
{
  // Kronecker property of Hermite interpolation, with the slope scaled by h.
  const FE_CubicHermite fe;
  const double h = 0.37;
  for (unsigned int i = 0; i < 4; ++i)
  {
    EXPECT_NEAR(fe.shape_value_on_cell(i, 0., h), i == 0 ? 1. : 0., 1e-15);
    EXPECT_NEAR(fe.shape_derivative_on_cell(i, 1, 0., h), i == 1 ? 1. : 0., 1e-14);
    EXPECT_NEAR(fe.shape_value_on_cell(i, 1., h), i == 2 ? 1. : 0., 1e-15);
    EXPECT_NEAR(fe.shape_derivative_on_cell(i, 1, 1., h), i == 3 ? 1. : 0., 1e-14);
  }
}

TEST(HermiteElement, FEValuesReproduceACubicOnANonUniformMesh)
{
  // Cubics lie in the Hermite space: FEValues must return the exact value,
  // first and second derivative at every quadrature point (round-off only).
  Triangulation<1> tria;
  make_nonuniform_mesh(tria);
  const FE_CubicHermite fe;
  DoFHandler<1> dofs(tria);
  dofs.distribute_dofs(fe);
  ASSERT_EQ(dofs.n_dofs(), 10u); // 5 vertices x (value, slope)
  const Vector<double> u = hermite_interpolant(dofs, cubic, cubic_d1);

  const QGauss<1> quadrature(5);
  FEValues<1> fe_values(fe, quadrature,
                        update_values | update_gradients | update_hessians |
                            update_quadrature_points);
  std::vector<double> values(quadrature.size());
  std::vector<Tensor<1, 1>> gradients(quadrature.size());
  std::vector<Tensor<2, 1>> hessians(quadrature.size());
  for (const auto& cell : dofs.active_cell_iterators())
  {
    fe_values.reinit(cell);
    fe_values.get_function_values(u, values);
    fe_values.get_function_gradients(u, gradients);
    fe_values.get_function_hessians(u, hessians);
    for (unsigned int q = 0; q < quadrature.size(); ++q)
    {
      const double x = fe_values.quadrature_point(q)[0];
      EXPECT_NEAR(values[q], cubic(x), 1e-13);
      EXPECT_NEAR(gradients[q][0], cubic_d1(x), 1e-12);
      EXPECT_NEAR(hessians[q][0][0], cubic_d2(x), 1e-11);
    }
  }
}

TEST(HermiteElement, GlobalFunctionsAreC1AcrossVertices)
{
  // For any coefficient vector, value and slope agree from both sides of
  // every interior vertex (slope jump = 0 to round-off on a non-uniform mesh).
  Triangulation<1> tria;
  make_nonuniform_mesh(tria);
  const FE_CubicHermite fe;
  DoFHandler<1> dofs(tria);
  dofs.distribute_dofs(fe);
  Vector<double> u(dofs.n_dofs());
  std::mt19937 random(42);
  std::uniform_real_distribution<double> uniform(-1., 1.);
  for (auto& x : u)
    x = uniform(random);

  const Quadrature<1> ends(std::vector<Point<1>>{Point<1>(0.), Point<1>(1.)});
  FEValues<1> fe_values(fe, ends, update_values | update_gradients | update_hessians);
  std::map<double, std::vector<std::array<double, 3>>> at_vertex;
  std::vector<double> values(2);
  std::vector<Tensor<1, 1>> gradients(2);
  std::vector<Tensor<2, 1>> hessians(2);
  for (const auto& cell : dofs.active_cell_iterators())
  {
    fe_values.reinit(cell);
    fe_values.get_function_values(u, values);
    fe_values.get_function_gradients(u, gradients);
    fe_values.get_function_hessians(u, hessians);
    for (unsigned int v = 0; v < 2; ++v)
      at_vertex[cell->vertex(v)[0]].push_back(
          {{values[v], gradients[v][0], hessians[v][0][0]}});
  }
  unsigned int interior = 0;
  double largest_curvature_jump = 0.;
  for (const auto& [x, sides] : at_vertex)
    if (sides.size() == 2)
    {
      ++interior;
      EXPECT_NEAR(sides[0][0], sides[1][0], 1e-14) << "value jump at x = " << x;
      EXPECT_NEAR(sides[0][1], sides[1][1], 1e-13) << "slope jump at x = " << x;
      largest_curvature_jump =
          std::max(largest_curvature_jump, std::abs(sides[0][2] - sides[1][2]));
    }
  EXPECT_EQ(interior, 3u);
  // The element is C1, not C2: random data has curvature jumps of order one.
  EXPECT_GT(largest_curvature_jump, 0.1);
}

TEST(HermiteElement, WorksWithAffineConstraintsAndDataOut)
{
  // A simply supported beam EI w'''' = q0 on [0, 1] assembled the deal.II way:
  // AffineConstraints fix the value dofs at both ends (not the slopes: w'' = 0
  // is natural), distribute_local_to_global, UMFPACK. Cubic Hermite elements
  // reproduce the quartic solution w = q0 x (1 - 2x^2 + x^3) / (24 EI) at the
  // vertices exactly (nodal exactness in 1D). DataOut writes the field.
  Triangulation<1> tria;
  GridGenerator::subdivided_hyper_cube(tria, 8, 0., 1.);
  const FE_CubicHermite fe;
  DoFHandler<1> dofs(tria);
  dofs.distribute_dofs(fe);
  AffineConstraints<double> constraints;
  for (const auto& cell : dofs.active_cell_iterators())
    for (unsigned int v = 0; v < 2; ++v)
      if (cell->at_boundary(v))
        constraints.add_line(cell->vertex_dof_index(v, 0)); // value only
  constraints.close();
  EXPECT_EQ(constraints.n_constraints(), 2u);

  DynamicSparsityPattern dsp(dofs.n_dofs());
  DoFTools::make_sparsity_pattern(dofs, dsp, constraints, false);
  SparsityPattern pattern;
  pattern.copy_from(dsp);
  SparseMatrix<double> K(pattern);
  Vector<double> f(dofs.n_dofs()), w(dofs.n_dofs());
  const double EI = 2., q0 = 3.;
  const QGauss<1> quadrature(4);
  FEValues<1> fe_values(fe, quadrature,
                        update_values | update_hessians | update_JxW_values);
  FullMatrix<double> local_matrix(4, 4);
  Vector<double> local_rhs(4);
  std::vector<types::global_dof_index> local_dofs(4);
  for (const auto& cell : dofs.active_cell_iterators())
  {
    fe_values.reinit(cell);
    local_matrix = 0.;
    local_rhs = 0.;
    for (unsigned int q = 0; q < quadrature.size(); ++q)
      for (unsigned int i = 0; i < 4; ++i)
      {
        local_rhs(i) += q0 * fe_values.shape_value(i, q) * fe_values.JxW(q);
        for (unsigned int j = 0; j < 4; ++j)
          local_matrix(i, j) += EI * fe_values.shape_hessian(i, q)[0][0] *
                                fe_values.shape_hessian(j, q)[0][0] * fe_values.JxW(q);
      }
    cell->get_dof_indices(local_dofs);
    constraints.distribute_local_to_global(local_matrix, local_rhs, local_dofs, K, f);
  }
  SparseDirectUMFPACK solver;
  solver.initialize(K);
  solver.vmult(w, f);
  constraints.distribute(w);
  for (const auto& cell : dofs.active_cell_iterators())
    for (unsigned int v = 0; v < 2; ++v)
    {
      const double x = cell->vertex(v)[0];
      EXPECT_NEAR(w(cell->vertex_dof_index(v, 0)),
                  q0 * x * (1. - 2. * x * x + x * x * x) / (24. * EI), 1e-14);
      EXPECT_NEAR(w(cell->vertex_dof_index(v, 1)),
                  q0 * (1. - 6. * x * x + 4. * x * x * x) / (24. * EI), 1e-13);
    }

  DataOut<1> data_out;
  data_out.attach_dof_handler(dofs);
  data_out.add_data_vector(w, "w");
  data_out.build_patches(4);
  std::ostringstream vtu;
  data_out.write_vtu(vtu);
  // 8 cells x 5 points per patch, every value from the C1 field.
  EXPECT_NE(vtu.str().find("NumberOfPoints=\"40\""), std::string::npos);
}
