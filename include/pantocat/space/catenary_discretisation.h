#pragma once

#include <pantocat/catenary/catenary_parameters.h>
#include <pantocat/lac/sparse_row.h>
#include <pantocat/space/discretisation_parameters.h>
#include <pantocat/space/smoothed_delta.h>
#include <pantocat/space/stitch_wire_space.h>
#include <pantocat/system/block_operator.h>
#include <pantocat/system/semi_discrete_system.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace pantocat
{
/// The two wires of the catenary.
enum class Wire
{
  carrier,
  contact_wire
};

/// Name of @p wire's body and block: "carrier" or "contact wire".
const char* block_name(Wire wire);

/**
 * Coefficients of the terms of the weak form (16)/(17) of one wire (or of
 * the difference operators (29)/(30)) that add_terms() adds:
 *   mass rho A, damping beta, tension T, bending E I, and the weight per
 *   length rho A g of the distributed gravity load.
 * A zero coefficient adds nothing: the scene's effects each add their own term.
 */
struct WireTerms
{
  double mass = 0.;
  double damping = 0.;
  double tension = 0.;
  double bending = 0.;
  double weight = 0.;
};

/**
 * Space discretisation of the catenary (Sec. 4): turns the wires of (2), (3)
 * into the semi-discrete operators (29), (30) and gives the rows that couple
 * the wires to droppers (31) and to the pantograph (32), (33).
 *
 * Unknowns are free coefficients only. The carrier is written as
 * w_c(x,t) = l_c + u_c(x,t), so that (3) becomes homogeneous for both wires:
 * the tension operator does not see the constant l_c, which then appears only
 * in the dropper constraints (5).
 *
 * Implementations: FemCatenary (Sec. 4.2), FdmCatenary (Sec. 4.3).
 */
class CatenaryDiscretisation
{
public:
  CatenaryDiscretisation(const CatenaryParameters& catenary,
                         const DiscretisationParameters& discretisation);
  virtual ~CatenaryDiscretisation() = default;

  virtual SpaceMethod method() const = 0;

  /**
   * True if @p wire's discretisation carries a bending term: always for FDM
   * (the five-point stencil) and for the FEM contact wire (C1 Hermite); the
   * FEM carrier only with Messenger element = cubic Hermite.
   */
  virtual bool has_bending_element(Wire wire) const = 0;

  /// Number of free unknowns of @p wire.
  virtual unsigned int n_dofs(Wire wire) const = 0;

  /**
   * Mass, damping, stiffness (tension, and bending for the contact wire) and
   * the distributed gravity load of @p wire with all the data of the wire:
   * initialize_operator() and add_terms() with every term. Point loads of
   * clamps and droppers are added by the scene through point_row().
   */
  void assemble(Wire wire, BlockOperator& op) const;

  /**
   * The sparsity pattern of @p wire and zero M, D, K, load; wide enough for
   * the bending term if @p with_bending (the FDM stencil of the fourth
   * derivative has five points).
   */
  virtual void initialize_operator(Wire wire, bool with_bending,
                                   BlockOperator& op) const = 0;

  /// Adds the terms of (16)/(17) (FEM) or (29)/(30) (FDM) with the given coefficients.
  virtual void add_terms(Wire wire, const WireTerms& terms, BlockOperator& op) const = 0;

  /**
   * The unknowns of @p wire that represent the displacement @p w (with slope
   * @p dw, for the Hermite slope unknowns): nodal interpolation.
   */
  virtual void interpolate(Wire wire, const std::function<double(double)>& w,
                           const std::function<double(double)>& dw,
                           dealii::Vector<double>& q) const = 0;

  /**
   * Row r with r.q = u(x): the displacement of @p wire at @p x (for the carrier
   * without the constant l_c). These are the rows of H_c and H_w in (31).
   */
  virtual SparseRow point_row(Wire wire, double x) const = 0;

  /**
   * Row r_k of the contact wire with r_k.q = int delta^{(k)}(x - x_c) w_w(x) dx,
   * k = 0, 1, 2, for the configured load shape: r_0 is F_w of (33), and
   * dF_w/dt = -x_p' r_1, d^2F_w/dt^2 = x_p'^2 r_2 - x_p'' r_1.
   */
  virtual void load_row(double x_c, unsigned int k, SparseRow& row) const = 0;
  /// The rows r_k, k = @p first_k .. first_k + count - 1, into *rows[0] ..
  /// (one load_row() each unless a discretisation shares their work).
  virtual void load_rows(double x_c, unsigned int first_k, unsigned int count,
                         SparseRow* const* rows) const
  {
    for (unsigned int r = 0; r < count; ++r)
      load_row(x_c, first_k + r, *rows[r]);
  }

  /**
   * The name of @p wire's block in the system: block_name(), after the
   * section's name in a line of several ("section 2 contact wire").
   */
  std::string wire_block_name(Wire wire) const;
  /// The name of the block of the section's stitch wires.
  std::string stitch_block_name() const;

  /**
   * The k-th x-derivative (k = 0, 1, 2) of the contact wire's reference
   * height, the support chord h of CatenaryParameters::support_chord(),
   * weighted by the load shape as F_w weights the unknowns:
   * int delta^{(0)}(y - x) h^{(k)}(y) dy (h'' being the chord's kinks), or
   * h^{(k)}(x) for a point load. The height of the contact point is this plus
   * F_w q_w (33).
   */
  double reference_height(double x, unsigned int k) const;

  /// The displacement w(x) of @p wire (with l_c for the carrier) for the unknowns @p q of
  /// that wire.
  double displacement(Wire wire, const dealii::Vector<double>& q, double x) const;

  /// Vertices x_0 < ... < x_{N+1} of the grid.
  std::vector<double> grid_points() const;

  unsigned int n_intervals() const { return discretisation.n_intervals; }
  /// L / N, kept: the contact's rows ask for it at every evaluation.
  double cell_size() const { return dx; }
  const CatenaryParameters& catenary_parameters() const { return catenary; }
  const DiscretisationParameters& discretisation_parameters() const
  {
    return discretisation;
  }
  const SmoothedDelta& smoothed_delta() const { return delta; }
  /// The stitch wires of the section on their own grids (none for a simple catenary).
  const StitchWireSpace& stitch_wires() const { return stitch; }

protected:
  const WireParameters& wire_parameters(Wire wire) const;

  CatenaryParameters catenary;
  DiscretisationParameters discretisation;
  SmoothedDelta delta;
  double dx; ///< L / N
  StitchWireSpace stitch;
  /// The supports and the support chord's kinks there, for reference_height().
  std::vector<double> supports, chord_kinks;
};

/**
 * Row r with r.q = w(x) of @p wire in the numbering of @p system (for the
 * carrier without l_c); empty if the system has no such block (a wire the
 * scene holds rigid: its displacement is 0).
 */
SparseRow wire_point_row(const CatenaryDiscretisation& discretisation,
                         const SemiDiscreteSystem& system, Wire wire, double x);

/**
 * Row r with r.q = u_s(x) of stitch wire @p i in the numbering of @p system
 * (from l_c, as the carrier's); empty if the system has no stitch wires.
 */
SparseRow stitch_wire_point_row(const CatenaryDiscretisation& discretisation,
                                const SemiDiscreteSystem& system, unsigned int i,
                                double x);

/**
 * The row H of the upper end of dropper @p j in the numbering of @p system:
 * the wire it hangs from at its position, its stitch wire's (stitched
 * catenary) or else the carrier's (H_c of (31)); with l_c, H q + l_c is the
 * height of the dropper's upper clamp.
 */
SparseRow dropper_upper_row(const CatenaryDiscretisation& discretisation,
                            const SemiDiscreteSystem& system, unsigned int j);

/// FEM or FDM, as the parameters say.
std::unique_ptr<CatenaryDiscretisation>
create_catenary_discretisation(const CatenaryParameters& catenary,
                               const DiscretisationParameters& discretisation);
} // namespace pantocat
