#include <pantocat/base/input_error.h>
#include <pantocat/constrained/reference_constrained_operator.h>

#include <deal.II/lac/lapack_full_matrix.h>

#include <cmath>
#include <sstream>

namespace pantocat
{
namespace
{
/// Entry @p i of @p values, 0 if it is empty (no entry given).
double entry(const std::vector<double>& values, const unsigned int i)
{
  return values.empty() ? 0. : values[i];
}

std::string singular_system(const double t, const char* what)
{
  std::ostringstream s;
  s << "the active constraints are linearly dependent at t = " << t << " s (" << what
    << ")";
  return s.str();
}
} // namespace

ReferenceConstrainedOperator::ReferenceConstrainedOperator(
    const SemiDiscreteSystem& system, const Definition& d)
    : ConstrainedOperator(system), definition(d), columns(system.n_constraints()),
      column_current(system.n_constraints(), 0)
{
  A.reinit(*system.sparsity);
  A.add(d.stiffness, system.stiffness);
  A.add(d.damping, system.damping);
  A.add(d.mass, system.mass);
  try
  {
    factor.initialize(A);
  }
  catch (const std::exception&)
  {
    throw SimulationError("the " + d.what + " is singular (UMFPACK)");
  }
}

void ReferenceConstrainedOperator::set_rows(const std::vector<ConstraintState>& r,
                                            const double t)
{
  if (rows == &r && time == t)
    return;
  rows = &r;
  time = t;
  // The columns of constant rows stay; the moving ones are solved again.
  for (unsigned int i = 0; i < column_current.size(); ++i)
    if (system.constraints[i]->depends_on_time())
      column_current[i] = 0;
}

const dealii::Vector<double>& ReferenceConstrainedOperator::column(const unsigned int i)
{
  if (!column_current[i])
  {
    columns[i].reinit(system.n_dofs());
    (*rows)[i].G.add_transpose_to(columns[i], 1.);
    factor.solve(columns[i]);
    column_current[i] = 1;
  }
  return columns[i];
}

void ReferenceConstrainedOperator::apply_inverse(dealii::Vector<double>& x) const
{
  factor.solve(x);
}

void ReferenceConstrainedOperator::solve_history(const double t,
                                                 const dealii::Vector<double>& h,
                                                 const dealii::Vector<double>& r,
                                                 dealii::Vector<double>& out)
{
  out.reinit(system.n_dofs(), true);
  system.load_at(t, out);
  system.mass.vmult_add(out, h);
  system.damping.vmult_add(out, r);
  factor.solve(out);
}

void ReferenceConstrainedOperator::solve_multipliers(const std::vector<unsigned int>& set,
                                                     std::vector<double>& y,
                                                     const char* what)
{
  const unsigned int p = set.size();
  std::vector<double> solution(system.n_constraints(), 0.);
  if (p > 0)
  {
    dealii::LAPACKFullMatrix<double> Z(p, p);
    dealii::Vector<double> b(p);
    for (unsigned int a = 0; a < p; ++a)
    {
      const unsigned int i = set[a];
      const ConstraintState& row = (*rows)[i];
      const double e = entry(definition.rate_weight, i);
      for (unsigned int c = 0; c < p; ++c)
      {
        const dealii::Vector<double>& x = column(set[c]);
        Z(a, c) = row.G.dot(x) + (e != 0. ? e * row.G_t.dot(x) : 0.);
      }
      Z(a, a) += entry(definition.compliance, i);
      b(a) = y[i];
    }
    try
    {
      Z.compute_lu_factorization();
    }
    catch (const std::exception&)
    {
      throw SimulationError(singular_system(time, what));
    }
    Z.solve(b);
    for (unsigned int a = 0; a < p; ++a)
    {
      if (!std::isfinite(b(a)))
        throw SimulationError(singular_system(time, what));
      solution[set[a]] = b(a);
    }
  }
  y.swap(solution);
}

void ReferenceConstrainedOperator::add_columns(const std::vector<double>& y,
                                               dealii::Vector<double>& x)
{
  dealii::Vector<double> w(system.n_dofs());
  bool any = false;
  for (unsigned int i = 0; i < y.size(); ++i)
    if (y[i] != 0.)
    {
      (*rows)[i].G.add_transpose_to(w, y[i]);
      any = true;
    }
  if (!any)
    return;
  factor.solve(w);
  x += w;
}
} // namespace pantocat
