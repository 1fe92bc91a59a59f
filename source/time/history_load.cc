#include <pantocat/time/history_load.h>

namespace pantocat
{
HistoryLoad::HistoryLoad(const SemiDiscreteSystem& system) : load(system.load)
{
  row_start.assign(1, 0);
  for (unsigned int i = 0; i < system.n_dofs(); ++i)
  {
    auto d = system.damping.begin(i);
    for (auto m = system.mass.begin(i); m != system.mass.end(i); ++m, ++d)
    {
      column.push_back(m->column());
      mass.push_back(m->value());
      damping.push_back(d->value());
    }
    row_start.push_back(column.size());
  }
}

void HistoryLoad::apply(const dealii::Vector<double>& h, const dealii::Vector<double>& r,
                        InterleavedColumns& out, const unsigned int k) const
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
} // namespace pantocat
