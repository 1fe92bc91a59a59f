#pragma once

#include <pantocat/lac/interleaved_columns.h>
#include <pantocat/system/semi_discrete_system.h>

#include <deal.II/lac/vector.h>

#include <vector>

namespace pantocat
{
/**
 * f + M h + D r in one pass over the sparsity pattern that M and D share:
 * the known part of the right-hand side of an implicit step (the history
 * terms of BDF-2 and of the generalized-alpha method), written straight
 * into one column of a batch of right-hand sides.
 */
class HistoryLoad
{
public:
  explicit HistoryLoad(const SemiDiscreteSystem& system);

  /// Column k of @p out = f + M h + D r.
  void apply(const dealii::Vector<double>& h, const dealii::Vector<double>& r,
             InterleavedColumns& out, unsigned int k) const;

private:
  dealii::Vector<double> load;
  std::vector<unsigned int> row_start, column;
  std::vector<double> mass, damping;
};
} // namespace pantocat
