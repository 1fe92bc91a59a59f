#pragma once

#include <pantocat/system/semi_discrete_system.h>
#include <pantocat/lac/sparse_row.h>

#include <vector>

namespace pantocat
{
/**
 * D M^-1 applied to a sparse vector, where the structure of the bodies makes
 * the result sparse, as the GGL terms of the implicit integrators need it
 * (D M^-1 G^T in the columns of (38)): per block of the semi-discrete system
 *  - mass-proportional damping D = gamma M (the FEM wires: beta / rho A):
 *    D M^-1 r = gamma r;
 *  - a diagonal mass matrix (FDM wires, lumped pantograph): the columns of D
 *    at the entries of r, scaled by 1 / M_jj.
 * A block with neither structure is "general": apply() then declines, and the
 * caller uses M^-1 and D on full vectors.
 */
class DampingOverMass
{
public:
  explicit DampingOverMass(const SemiDiscreteSystem& system);

  /// out = (D M^-1 r^T)^T if every entry of @p r lies in a structured block.
  bool apply(const SparseRow& r, SparseRow& out) const;

  /// True if every block is structured (apply() never declines).
  bool all_structured() const;

private:
  enum class Structure
  {
    proportional,
    diagonal_mass,
    general
  };
  struct Block
  {
    unsigned int first = 0, last = 0;
    Structure structure = Structure::general;
    double gamma = 0.; ///< D = gamma M (proportional)
  };
  const Block& block_of(unsigned int i) const;

  const SemiDiscreteSystem& system;
  std::vector<Block> blocks;
};
} // namespace pantocat
