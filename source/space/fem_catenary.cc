#include <pantocat/space/fem_catenary.h>

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace pantocat
{
namespace
{
constexpr unsigned int invalid = dealii::numbers::invalid_unsigned_int;
}

FemCatenary::FemCatenary(const CatenaryParameters& catenary,
                         const DiscretisationParameters& discretisation)
    : CatenaryDiscretisation(catenary, discretisation), carrier_fe(1)
{
  dealii::GridGenerator::subdivided_hyper_cube(triangulation, discretisation.n_intervals,
                                               0., catenary.length());
  for (const auto& cell : triangulation.active_cell_iterators())
    cells.push_back(cell);
  std::sort(cells.begin(), cells.end(),
            [](const auto& a, const auto& b)
            { return a->vertex(0)[0] < b->vertex(0)[0]; });
  for (const auto& cell : cells)
    cell_start.push_back(cell->vertex(0)[0]);
  cell_start.push_back(cells.back()->vertex(1)[0]);

  for (auto* s : {&carrier_space, &wire_space})
  {
    s->dofs.reinit(triangulation);
    const bool hermite = s == &wire_space || has_bending_element(Wire::carrier);
    s->dofs.distribute_dofs(
        hermite ? static_cast<const dealii::FiniteElement<1>&>(wire_fe)
                : static_cast<const dealii::FiniteElement<1>&>(carrier_fe));
    // Eliminate the value dof (component 0 of the vertex) at both ends, Eq. (3).
    std::vector<bool> eliminated(s->dofs.n_dofs(), false);
    for (const auto& cell : s->dofs.active_cell_iterators())
      for (unsigned int v = 0; v < 2; ++v)
        if (cell->at_boundary(v))
          eliminated[cell->vertex_dof_index(v, 0)] = true;
    s->cell_dofs.resize(cells.size());
    for (unsigned int c = 0; c < cells.size(); ++c)
    {
      const typename dealii::DoFHandler<1>::active_cell_iterator cell(
          &triangulation, cells[c]->level(), cells[c]->index(), &s->dofs);
      s->cell_dofs[c].resize(s->dofs.get_fe().n_dofs_per_cell());
      cell->get_dof_indices(s->cell_dofs[c]);
    }
    s->free.assign(s->dofs.n_dofs(), invalid);
    for (unsigned int i = 0; i < s->dofs.n_dofs(); ++i)
      if (!eliminated[i])
        s->free[i] = s->n_free++;
  }
}

const FemCatenary::WireSpace& FemCatenary::space(const Wire wire) const
{
  return wire == Wire::carrier ? carrier_space : wire_space;
}

unsigned int FemCatenary::n_dofs(const Wire wire) const
{
  return space(wire).n_free;
}

const dealii::DoFHandler<1>& FemCatenary::dof_handler(const Wire wire) const
{
  return space(wire).dofs;
}

const std::vector<unsigned int>& FemCatenary::free_index(const Wire wire) const
{
  return space(wire).free;
}

void FemCatenary::initialize_operator(const Wire wire, bool /*with_bending*/,
                                      BlockOperator& op) const
{
  // The Hermite pattern already couples all dofs of a cell: bending adds no entries.
  const WireSpace& s = space(wire);
  std::vector<dealii::types::global_dof_index> dofs(s.dofs.get_fe().n_dofs_per_cell());
  op.name = wire_block_name(wire);
  dealii::DynamicSparsityPattern dsp(s.n_free, s.n_free);
  for (const auto& cell : s.dofs.active_cell_iterators())
  {
    cell->get_dof_indices(dofs);
    for (auto i : dofs)
      for (auto j : dofs)
        if (s.free[i] != invalid && s.free[j] != invalid)
          dsp.add(s.free[i], s.free[j]);
  }
  op.sparsity->copy_from(dsp);
  op.reinit_matrices(s.n_free);
  op.mass_is_diagonal = false;
}

namespace
{
/**
 * The values of a matrix by the global index of its sparsity pattern, copied
 * out of it and back: an addition to an entry found once per cell instead of
 * once per addition (a binary search in its row each time), the same
 * additions in the same order.
 */
class EntryValues
{
public:
  /// The values of @p matrix if @p used, else none (and nothing is stored back).
  EntryValues(dealii::SparseMatrix<double>& matrix, const bool used) : matrix(matrix)
  {
    if (!used)
      return;
    values.reserve(matrix.n_nonzero_elements());
    for (unsigned int i = 0; i < matrix.m(); ++i)
      for (auto it = matrix.begin(i), end = matrix.end(i); it != end; ++it)
        values.push_back(it->value());
  }
  void add(const std::size_t entry, const double value) { values[entry] += value; }
  /// Writes the values back into the matrix.
  void store()
  {
    if (values.empty())
      return;
    std::size_t e = 0;
    for (unsigned int i = 0; i < matrix.m(); ++i)
      for (auto it = matrix.begin(i), end = matrix.end(i); it != end; ++it)
        it->value() = values[e++];
  }

private:
  dealii::SparseMatrix<double>& matrix;
  std::vector<double> values;
};

/// One cell's contributions to M, D and K of a wire (weak form (16)), summed over
/// the quadrature points.
struct CellMatrices
{
  explicit CellMatrices(const unsigned int n)
      : n(n), mass(n * n), damping(n * n), stiffness(n * n)
  {
  }

  void compute(const dealii::FEValues<1>& fe_values, const WireTerms& t, const bool beam)
  {
    std::fill(mass.begin(), mass.end(), 0.);
    std::fill(damping.begin(), damping.end(), 0.);
    std::fill(stiffness.begin(), stiffness.end(), 0.);
    for (unsigned int q = 0; q < fe_values.n_quadrature_points; ++q)
    {
      const double jxw = fe_values.JxW(q);
      for (unsigned int i = 0; i < n; ++i)
        for (unsigned int j = 0; j < n; ++j)
        {
          const double vivj =
              fe_values.shape_value(i, q) * fe_values.shape_value(j, q) * jxw;
          mass[i * n + j] += t.mass * vivj;
          damping[i * n + j] += t.damping * vivj;
          // T int v' w' + EI int v'' w''; products first, so that K is
          // symmetric to the last bit.
          double k =
              t.tension * (fe_values.shape_grad(i, q)[0] * fe_values.shape_grad(j, q)[0]);
          if (beam)
            k += t.bending * (fe_values.shape_hessian(i, q)[0][0] *
                              fe_values.shape_hessian(j, q)[0][0]);
          stiffness[i * n + j] += k * jxw;
        }
    }
  }

  unsigned int n;
  std::vector<double> mass, damping, stiffness;
};
/**
 * Whether a cell of @p length, whose vertices lie within @p reach of the
 * origin, has the length @p kept up to the rounding of its vertices, or to
 * 1e-12 of its length. Each vertex is within half an ulp of its position,
 * so two cells of one uniform grid differ by up to 2 ulp(reach) <= 4.4e-16
 * reach (bound: 4 eps reach = 8.9e-16 reach). With h = 0.04 m one ulp is
 * already 2.8e-12 h beyond 512 m, more than the relative bound allows.
 */
bool same_cell_length(const double length, const double kept, const double reach)
{
  const double rounding = 4. * std::numeric_limits<double>::epsilon() * reach;
  return std::abs(length - kept) <= std::max(1e-12 * std::abs(kept), rounding);
}
} // namespace

void FemCatenary::add_terms(const Wire wire, const WireTerms& t, BlockOperator& op) const
{
  const WireSpace& s = space(wire);
  const dealii::FiniteElement<1>& fe = s.dofs.get_fe();
  const unsigned int n_local = fe.n_dofs_per_cell();
  std::vector<dealii::types::global_dof_index> dofs(n_local);
  // Linear Lagrange (the paper's carrier) has no second derivatives inside a cell.
  const bool beam = has_bending_element(wire) && t.bending != 0.;
  const dealii::QGauss<1> quadrature(4);
  dealii::FEValues<1> fe_values(
      fe, quadrature,
      dealii::update_values | dealii::update_gradients |
          (beam ? dealii::update_hessians : dealii::update_default) |
          dealii::update_JxW_values);
  EntryValues mass(op.mass, t.mass != 0.), damping(op.damping, t.damping != 0.),
      stiffness(op.stiffness, t.tension != 0. || beam);
  // The cell matrices, kept for the next cell of the same length: on a
  // uniform grid every cell adds the same values to the bit, so equal rows
  // repeat exactly (what PatternOperators and DiagonalForceSweep look for),
  // instead of differing in the last bits with each cell's vertices.
  CellMatrices local(n_local);
  double local_length = -1.;
  for (const auto& cell : s.dofs.active_cell_iterators())
  {
    fe_values.reinit(cell);
    cell->get_dof_indices(dofs);
    const double x0 = cell->vertex(0)[0], x1 = cell->vertex(1)[0];
    const double length = x1 - x0;
    if (!same_cell_length(length, local_length, std::max(std::abs(x0), std::abs(x1))))
    {
      local.compute(fe_values, t, beam);
      local_length = length;
    }
    for (unsigned int q = 0; q < quadrature.size(); ++q)
    {
      const double jxw = fe_values.JxW(q);
      for (unsigned int i = 0; i < n_local; ++i)
        if (t.weight != 0. && s.free[dofs[i]] != invalid)
          op.load(s.free[dofs[i]]) -= t.weight * fe_values.shape_value(i, q) * jxw;
    }
    for (unsigned int i = 0; i < n_local; ++i)
      for (unsigned int j = 0; j < n_local; ++j)
      {
        if (s.free[dofs[i]] == invalid || s.free[dofs[j]] == invalid)
          continue;
        const std::size_t e = (*op.sparsity)(s.free[dofs[i]], s.free[dofs[j]]);
        const std::size_t ij = i * n_local + j;
        if (t.mass != 0.)
          mass.add(e, local.mass[ij]);
        if (t.damping != 0.)
          damping.add(e, local.damping[ij]);
        if (local.stiffness[ij] != 0.)
          stiffness.add(e, local.stiffness[ij]);
      }
  }
  for (EntryValues* values : {&mass, &damping, &stiffness})
    values->store();
}

void FemCatenary::interpolate(const Wire wire, const std::function<double(double)>& w,
                              const std::function<double(double)>& dw,
                              dealii::Vector<double>& q) const
{
  const WireSpace& s = space(wire);
  q.reinit(s.n_free);
  const unsigned int components = s.dofs.get_fe().n_dofs_per_vertex();
  for (const auto& cell : s.dofs.active_cell_iterators())
    for (unsigned int v = 0; v < 2; ++v)
    {
      const double x = cell->vertex(v)[0];
      for (unsigned int c = 0; c < components; ++c)
      {
        const unsigned int I = s.free[cell->vertex_dof_index(v, c)];
        if (I != invalid)
          q(I) = c == 0 ? w(x) : dw(x);
      }
    }
}

unsigned int FemCatenary::cell_index(const double x) const
{
  // The last cell starting at or before x (cell_start: the cells' left ends
  // in order, then the right end).
  const auto it = std::upper_bound(cell_start.begin(), cell_start.end() - 1, x);
  const unsigned int c = it == cell_start.begin() ? 0 : (it - cell_start.begin()) - 1;
  return std::min<unsigned int>(c, cells.size() - 1);
}

const std::vector<dealii::types::global_dof_index>&
FemCatenary::local_dofs(const Wire wire, const unsigned int c) const
{
  return space(wire).cell_dofs[c];
}

double FemCatenary::shape(const Wire wire, const unsigned int c, const unsigned int i,
                          const unsigned int k, const double x) const
{
  const double x0 = cell_start[c];
  const double h = cell_start[c + 1] - x0;
  const double xi = (x - x0) / h;
  if (has_bending_element(wire)) // C1 Hermite
    return wire_fe.shape_derivative_on_cell(i, k, xi, h);
  // Linear Lagrange: value or slope; higher derivatives vanish inside a cell.
  if (k == 0)
    return carrier_fe.shape_value(i, dealii::Point<1>(xi));
  return k == 1 ? carrier_fe.shape_grad(i, dealii::Point<1>(xi))[0] / h : 0.;
}

SparseRow FemCatenary::point_row(const Wire wire, const double x) const
{
  SparseRow row;
  const unsigned int c = cell_index(x);
  const auto& dofs = local_dofs(wire, c);
  for (unsigned int i = 0; i < dofs.size(); ++i)
  {
    const unsigned int I = space(wire).free[dofs[i]];
    const double v = shape(wire, c, i, 0, x);
    if (I != invalid && v != 0.)
      row.add(I, v);
  }
  return row;
}

void FemCatenary::full_load_row(const double x_c, const unsigned int k,
                                SparseRow& row) const
{
  full_load_rows(x_c, k, 1, &row);
}

template <typename Sink>
void FemCatenary::for_each_load_entry(const double x_c, const unsigned int first_k,
                                      const unsigned int count, Sink&& sink) const
{
  AssertThrow(count >= 1 && count <= 3, dealii::ExcMessage("one to three load rows"));
  if (discretisation.load_shape == LoadShape::point)
  {
    // int delta^{(k)}(x - x_c) v(x) dx = (-1)^k v^{(k)}(x_c)
    const unsigned int c = cell_index(x_c);
    const auto& dofs = local_dofs(Wire::contact_wire, c);
    for (unsigned int r = 0; r < count; ++r)
    {
      const unsigned int k = first_k + r;
      for (unsigned int i = 0; i < dofs.size(); ++i)
        sink(r, dofs[i], (k % 2 ? -1. : 1.) * shape(Wire::contact_wire, c, i, k, x_c));
    }
    return;
  }
  const double eps = delta.epsilon();
  const unsigned int first = cell_index(std::max(0., x_c - eps));
  const unsigned int last = cell_index(std::min(catenary.length(), x_c + eps));
  for (unsigned int c = first; c <= last; ++c)
  {
    const double x0 = cell_start[c], x1 = cell_start[c + 1];
    // Break points: cell ends and the spline knots x_c - eps, x_c, x_c + eps inside the
    // cell.
    std::array<double, 5> breaks{{std::max(x0, x_c - eps), std::min(x1, x_c + eps)}};
    unsigned int n_breaks = 2;
    for (const double knot : delta.knots())
      if (x_c + knot > breaks[0] && x_c + knot < breaks[1])
        breaks[n_breaks++] = x_c + knot;
    std::sort(breaks.begin(), breaks.begin() + n_breaks);
    // The shape values at each quadrature point serve every row.
    double local[3][4] = {};
    for (unsigned int p = 0; p + 1 < n_breaks; ++p)
    {
      const double a = breaks[p], length = breaks[p + 1] - breaks[p];
      if (length <= 0.)
        continue;
      for (unsigned int q = 0; q < gauss.size(); ++q)
      {
        const double x = a + length * gauss.point(q)[0];
        double v[4];
        for (unsigned int i = 0; i < 4; ++i)
          v[i] = shape(Wire::contact_wire, c, i, 0, x);
        for (unsigned int r = 0; r < count; ++r)
        {
          const double weight =
              length * gauss.weight(q) * delta.derivative(x - x_c, first_k + r);
          for (unsigned int i = 0; i < 4; ++i)
            local[r][i] += weight * v[i];
        }
      }
    }
    const auto& dofs = local_dofs(Wire::contact_wire, c);
    for (unsigned int r = 0; r < count; ++r)
      for (unsigned int i = 0; i < 4; ++i)
        sink(r, dofs[i], local[r][i]);
  }
}

void FemCatenary::full_load_rows(const double x_c, const unsigned int first_k,
                                 const unsigned int count, SparseRow* rows) const
{
  for (unsigned int r = 0; r < count; ++r)
    rows[r].clear();
  for_each_load_entry(x_c, first_k, count,
                      [&](const unsigned int r, const unsigned int dof,
                          const double value) { rows[r].add(dof, value); });
}

void FemCatenary::load_row(const double x_c, const unsigned int k, SparseRow& row) const
{
  SparseRow* const rows[1] = {&row};
  load_rows(x_c, k, 1, rows);
}

void FemCatenary::load_rows(const double x_c, const unsigned int first_k,
                            const unsigned int count, SparseRow* const* rows) const
{
  // Sum duplicates of shared vertex dofs and drop the eliminated ones, in
  // the order of the entries (as from full_load_rows()).
  const auto& free = wire_space.free;
  for (unsigned int r = 0; r < count; ++r)
    rows[r]->clear();
  for_each_load_entry(
      x_c, first_k, count,
      [&](const unsigned int r, const unsigned int dof, const double value)
      {
        const unsigned int I = free[dof];
        if (I == invalid)
          return;
        SparseRow& row = *rows[r];
        auto it = std::find(row.index.begin(), row.index.end(), I);
        if (it == row.index.end())
          row.add(I, value);
        else
          row.value[it - row.index.begin()] += value;
      });
}
} // namespace pantocat
