#pragma once

#include <pantocat/catenary/catenary_parameters.h>
#include <pantocat/lac/sparse_row.h>
#include <pantocat/system/block_operator.h>

#include <deal.II/fe/fe_q.h>

#include <vector>

namespace pantocat
{
struct WireTerms;

/**
 * The stitch wires of a section (StitchWire), discretised as strings: the
 * wave equation (2) with E I = 0 and the stitch wire's rho A, beta and T on
 * its length [x_a, x_b], in n equal linear Lagrange elements FE_Q<1>(1), n the
 * smallest number with elements no longer than the section's grid size h.
 * All nodes are unknowns, the ends included: each end is clamped to the
 * carrier by a constraint (the StitchWires effect), which also removes the
 * free string's rigid motion, so the stiffness of this block alone is
 * singular (BlockOperator::stiffness_is_definite = false).
 *
 * FEM (Sec. 4.2): the consistent mass of the weak form (16), point rows by
 * the shape functions at x. FDM (Sec. 4.3): the mass lumped to the nodes
 * (rho A h, half of it at the ends), so that M stays diagonal, and a point
 * belongs to the node whose control volume holds it, as the wires' nodes.
 * The stiffness T/h tridiag(-1, 2, -1) (T/h at an end) is the same in both.
 *
 * Like the carrier, a stitch wire's displacement u_s is measured from the
 * encumbrance l_c: its height is w_s = l_c + u_s. The stitch wires' unknowns
 * are one block, "stitch wires", the wires in order of their supports.
 */
class StitchWireSpace
{
public:
  /// Name of the block of the stitch wires' unknowns.
  static constexpr const char* block_name = "stitch wires";

  /// The stitch wires of @p catenary on elements of at most @p h [m];
  /// @p lumped: the FDM form (diagonal mass, nearest-node rows).
  StitchWireSpace(const CatenaryParameters& catenary, double h, bool lumped);

  unsigned int n_wires() const { return wires.size(); }
  /// Unknowns of all stitch wires.
  unsigned int n_dofs() const;
  /// Elements of stitch wire @p i.
  unsigned int n_elements(unsigned int i) const { return wires[i].n_elements; }
  /// Position [m] of node @p k (0 .. n_elements) of stitch wire @p i.
  double node_position(unsigned int i, unsigned int k) const;

  /// The sparsity pattern (tridiagonal per wire) and zero M, D, K, load.
  void initialize_operator(BlockOperator& op) const;
  /// Adds the terms of (16) with the coefficients @p terms on stitch wire @p i
  /// (bending is ignored: a string).
  void add_terms(unsigned int i, const WireTerms& terms, BlockOperator& op) const;
  /// Row r with r.q = u_s(x) of stitch wire @p i in the block's numbering.
  SparseRow point_row(unsigned int i, double x) const;

private:
  struct Grid
  {
    double start = 0., h = 0.;
    unsigned int n_elements = 0, first = 0; ///< first: its first unknown in the block
  };
  std::vector<Grid> wires;
  dealii::FE_Q<1> fe; ///< linear Lagrange: the shape functions of point_row()
  bool lumped;
};
} // namespace pantocat
