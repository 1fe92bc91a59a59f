#include <pantocat/space/catenary_discretisation.h>
#include <pantocat/space/stitch_wire_space.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <algorithm>
#include <cmath>

namespace pantocat
{
StitchWireSpace::StitchWireSpace(const CatenaryParameters& catenary, const double h,
                                 const bool lumped)
    : fe(1), lumped(lumped)
{
  unsigned int first = 0;
  for (const StitchWire& s : catenary.stitch_wires)
  {
    Grid g;
    g.start = s.start();
    // Elements no longer than h; 1e-9 keeps a length of k h at k elements.
    g.n_elements =
        std::max(1u, static_cast<unsigned int>(std::ceil(s.length / h - 1e-9)));
    g.h = s.length / g.n_elements;
    g.first = first;
    first += g.n_elements + 1;
    wires.push_back(g);
  }
}

unsigned int StitchWireSpace::n_dofs() const
{
  return wires.empty() ? 0 : wires.back().first + wires.back().n_elements + 1;
}

double StitchWireSpace::node_position(const unsigned int i, const unsigned int k) const
{
  return wires[i].start + k * wires[i].h;
}

void StitchWireSpace::initialize_operator(BlockOperator& op) const
{
  const unsigned int n = n_dofs();
  op.name = block_name;
  dealii::DynamicSparsityPattern dsp(n, n);
  for (const Grid& g : wires)
    for (unsigned int e = 0; e < g.n_elements; ++e)
      for (const unsigned int i : {g.first + e, g.first + e + 1})
        for (const unsigned int j : {g.first + e, g.first + e + 1})
          dsp.add(i, j);
  op.sparsity->copy_from(dsp);
  op.reinit_matrices(n);
  op.mass_is_diagonal = lumped;
  op.stiffness_is_definite = wires.empty();
}

namespace
{
/// Mass v_i v_j, stiffness v_i' v_j' and load v_i of one element of length
/// @p h (FE_Q<1>(1), QGauss(2): exact for these products).
struct ElementIntegrals
{
  explicit ElementIntegrals(const double h)
  {
    dealii::Triangulation<1> cell;
    dealii::GridGenerator::hyper_cube(cell, 0., h);
    const dealii::FE_Q<1> fe(1);
    const dealii::QGauss<1> quadrature(2);
    dealii::FEValues<1> values(fe, quadrature,
                               dealii::update_values | dealii::update_gradients |
                                   dealii::update_JxW_values);
    values.reinit(cell.begin_active());
    // Local shape function 0 belongs to vertex 0 (x = 0), 1 to vertex 1.
    for (unsigned int q = 0; q < quadrature.size(); ++q)
      for (unsigned int i = 0; i < 2; ++i)
      {
        load[i] += values.shape_value(i, q) * values.JxW(q);
        for (unsigned int j = 0; j < 2; ++j)
        {
          mass[i][j] +=
              values.shape_value(i, q) * values.shape_value(j, q) * values.JxW(q);
          stiffness[i][j] +=
              values.shape_grad(i, q)[0] * values.shape_grad(j, q)[0] * values.JxW(q);
        }
      }
  }
  double mass[2][2] = {}, stiffness[2][2] = {}, load[2] = {};
};
} // namespace

void StitchWireSpace::add_terms(const unsigned int w, const WireTerms& t,
                                BlockOperator& op) const
{
  const Grid& g = wires[w];
  const ElementIntegrals element(g.h);
  for (unsigned int e = 0; e < g.n_elements; ++e)
    for (unsigned int i = 0; i < 2; ++i)
    {
      const unsigned int I = g.first + e + i;
      op.load(I) -= t.weight * element.load[i];
      for (unsigned int j = 0; j < 2; ++j)
      {
        const unsigned int J = g.first + e + j;
        // Lumped (FDM): each row's mass on its diagonal, rho A h per node.
        const unsigned int mass_column = lumped ? I : J;
        if (t.mass != 0.)
          op.mass.add(I, mass_column, t.mass * element.mass[i][j]);
        if (t.damping != 0.)
          op.damping.add(I, mass_column, t.damping * element.mass[i][j]);
        if (t.tension != 0.)
          op.stiffness.add(I, J, t.tension * element.stiffness[i][j]);
      }
    }
}

SparseRow StitchWireSpace::point_row(const unsigned int w, const double x) const
{
  const Grid& g = wires[w];
  const double s = std::clamp((x - g.start) / g.h, 0., double(g.n_elements));
  SparseRow row;
  if (lumped) // the node whose control volume holds x
  {
    row.add(g.first + static_cast<unsigned int>(std::floor(s + 0.5)), 1.);
    return row;
  }
  const unsigned int e = std::min(static_cast<unsigned int>(s), g.n_elements - 1);
  const dealii::Point<1> xi(s - e);
  for (unsigned int i = 0; i < 2; ++i)
    if (const double v = fe.shape_value(i, xi); v != 0.)
      row.add(g.first + e + i, v);
  return row;
}
} // namespace pantocat
