#include <pantocat/constrained_fast/damping_over_mass.h>

#include <algorithm>
#include <cmath>

namespace pantocat
{
namespace
{
bool nearly_equal(const double a, const double b)
{
  return std::abs(a - b) <= 1e-13 * (std::abs(a) + std::abs(b));
}

/// True if M has no off-diagonal entry in rows [first, last).
bool mass_is_diagonal(const dealii::SparseMatrix<double>& M, unsigned int first,
                      unsigned int last)
{
  for (unsigned int i = first; i < last; ++i)
    for (auto it = M.begin(i); it != M.end(i); ++it)
      if (it->column() != i && it->value() != 0.)
        return false;
  return true;
}

/// True if D is symmetric in rows [first, last) (the columns of D are its rows).
bool is_symmetric(const dealii::SparseMatrix<double>& D, unsigned int first,
                  unsigned int last)
{
  for (unsigned int i = first; i < last; ++i)
    for (auto it = D.begin(i); it != D.end(i); ++it)
      if (!nearly_equal(it->value(), D.el(it->column(), i)))
        return false;
  return true;
}
} // namespace

DampingOverMass::DampingOverMass(const SemiDiscreteSystem& system) : system(system)
{
  const auto& M = system.mass;
  const auto& D = system.damping;
  for (const DofBlock& b : system.blocks)
  {
    Block block{b.first, b.first + b.size, Structure::general, 0.};
    if (b.size == 0)
      continue;
    // D = gamma M entry by entry (M and D share the system's sparsity pattern),
    // to round-off relative to the row's largest mass entry (entries of the
    // Hermite mass matrix that are sums of cancelling quadrature terms carry
    // round-off of that size).
    block.gamma = D.diag_element(b.first) / M.diag_element(b.first);
    bool proportional = true;
    for (unsigned int i = block.first; i < block.last && proportional; ++i)
    {
      double row_scale = 0.;
      for (auto m = M.begin(i); m != M.end(i); ++m)
        row_scale = std::max(row_scale, std::abs(m->value()));
      auto d = D.begin(i);
      for (auto m = M.begin(i); m != M.end(i); ++m, ++d)
        proportional = proportional && std::abs(d->value() - block.gamma * m->value()) <=
                                           1e-13 * std::abs(block.gamma) * row_scale;
    }
    if (proportional)
      block.structure = Structure::proportional;
    else if (mass_is_diagonal(M, block.first, block.last) &&
             is_symmetric(D, block.first, block.last))
      block.structure = Structure::diagonal_mass;
    blocks.push_back(block);
  }
}

const DampingOverMass::Block& DampingOverMass::block_of(const unsigned int i) const
{
  for (const Block& b : blocks)
    if (i >= b.first && i < b.last)
      return b;
  return blocks.back(); // not reached: the blocks cover all unknowns
}

bool DampingOverMass::all_structured() const
{
  for (const Block& b : blocks)
    if (b.structure == Structure::general)
      return false;
  return true;
}

bool DampingOverMass::apply(const SparseRow& r, SparseRow& out) const
{
  out.clear();
  for (std::size_t k = 0; k < r.size(); ++k)
  {
    const unsigned int j = r.index[k];
    const Block& b = block_of(j);
    switch (b.structure)
    {
    case Structure::proportional:
      out.add(j, b.gamma * r.value[k]);
      break;
    case Structure::diagonal_mass:
    {
      const double scaled = r.value[k] / system.mass.diag_element(j);
      for (auto it = system.damping.begin(j); it != system.damping.end(j); ++it)
        if (it->value() != 0.)
          out.add(it->column(), it->value() * scaled);
      break;
    }
    case Structure::general:
      out.clear();
      return false;
    }
  }
  return true;
}
} // namespace pantocat
