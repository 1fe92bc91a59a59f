#include <pantocat/system/pattern_operators.h>

namespace pantocat
{
PatternOperators::PatternOperators(const SemiDiscreteSystem& system)
    : system(system), load(system.load)
{
  row_start.assign(1, 0);
  for (unsigned int i = 0; i < system.n_dofs(); ++i)
  {
    auto d = system.damping.begin(i);
    auto k = system.stiffness.begin(i);
    for (auto m = system.mass.begin(i); m != system.mass.end(i); ++m, ++d, ++k)
    {
      column.push_back(m->column());
      mass.push_back(m->value());
      damping.push_back(d->value());
      stiffness.push_back(k->value());
    }
    row_start.push_back(column.size());
  }
}

void PatternOperators::set_time(const double t) const
{
  if (system.has_time_dependent_load())
    system.load_at(t, load);
}

void PatternOperators::history(const dealii::Vector<double>& h,
                               const dealii::Vector<double>& r, InterleavedColumns& out,
                               const unsigned int k) const
{
  const double* __restrict hh = h.begin();
  const double* __restrict rr = r.begin();
  for (unsigned int i = 0; i + 1 < row_start.size(); ++i)
  {
    double s = load[i];
    for (unsigned int e = row_start[i]; e < row_start[i + 1]; ++e)
      s += mass[e] * hh[column[e]] + damping[e] * rr[column[e]];
    out(i, k) = s;
  }
}

void PatternOperators::motion(const double* q, const double* v, const double* qp,
                              const double* vp, double* r_q, double* r_v) const
{
  for (unsigned int i = 0; i + 1 < row_start.size(); ++i)
  {
    double fq = 0., fv = -load[i];
    for (unsigned int e = row_start[i]; e < row_start[i + 1]; ++e)
    {
      const unsigned int j = column[e];
      fq += mass[e] * (qp[j] - v[j]);
      fv += mass[e] * vp[j] + damping[e] * v[j] + stiffness[e] * q[j];
    }
    r_q[i] = fq;
    r_v[i] = fv;
  }
}
} // namespace pantocat
