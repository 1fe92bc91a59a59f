#include <pantocat/time/constraint_response_cache.h>

namespace pantocat
{
ConstraintResponseCache::ConstraintResponseCache(const SparseDirectSolver& S,
                                                 const MassInverse& M,
                                                 const dealii::SparseMatrix<double>& D)
    : S(S), M(M), D(D), slot_of(D.m(), -1), wanted(D.m(), 0)
{
}

void ConstraintResponseCache::update(const std::vector<const SparseRow*>& rows)
{
  const unsigned int n = D.m();
  for (const SparseRow* row : rows)
    for (const unsigned int i : row->index)
      wanted[i] = 1;
  // Free the slots of unknowns no row touches any more.
  std::vector<unsigned int> kept;
  for (const unsigned int i : cached)
    if (wanted[i])
      kept.push_back(i);
    else
    {
      free_slots.push_back(slot_of[i]);
      slot_of[i] = -1;
    }
  cached.swap(kept);
  for (const SparseRow* row : rows)
    for (const unsigned int i : row->index)
    {
      wanted[i] = 0;
      if (slot_of[i] >= 0)
        continue;
      cached.push_back(i);
      if (free_slots.empty())
      {
        free_slots.push_back(pool.size());
        pool.emplace_back();
      }
      const int slot = free_slots.back();
      free_slots.pop_back();
      slot_of[i] = slot;
      Response& r = pool[slot];
      r.s.reinit(n);
      r.s(i) = 1.;
      S.solve(r.s);
      r.m.reinit(n);
      SparseRow unit;
      unit.add(i, 1.);
      M.apply_to_row(unit, r.m);
      r.t.reinit(n);
      D.vmult(r.t, r.m);
      S.solve(r.t);
      ++computed;
    }
}

const dealii::Vector<double>& ConstraintResponseCache::response(const unsigned int dof,
                                                                const Operator A) const
{
  const Response& r = pool[slot_of[dof]];
  return A == Operator::S ? r.s : (A == Operator::M ? r.m : r.t);
}

double ConstraintResponseCache::form(const SparseRow& l, const Operator A,
                                     const SparseRow& r) const
{
  double sum = 0.;
  for (std::size_t k = 0; k < r.size(); ++k)
    sum += r.value[k] * l.dot(response(r.index[k], A));
  return sum;
}

void ConstraintResponseCache::add(const Operator A, const SparseRow& r,
                                  const double factor, dealii::Vector<double>& y) const
{
  for (std::size_t k = 0; k < r.size(); ++k)
    if (r.value[k] != 0.)
      y.add(factor * r.value[k], response(r.index[k], A));
}
} // namespace pantocat
