#include <pantocat/analysis/static_equilibrium.h>
#include <pantocat/base/input_error.h>
#include <pantocat/base/number_format.h>
#include <pantocat/scene/carrier_supports.h>
#include <pantocat/scene/clamp_and_dropper_masses.h>
#include <pantocat/scene/scene_builder.h>
#include <pantocat/scene/steady_arms.h>
#include <pantocat/simulation/catenary_design.h>

#include <limits>

#include <algorithm>
#include <cmath>

namespace pantocat
{
namespace
{
/// Removes the constraints with the given indices from @p system.
void remove_constraints(SemiDiscreteSystem& system, std::vector<unsigned int> indices)
{
  std::sort(indices.rbegin(), indices.rend());
  for (const unsigned int i : indices)
    system.constraints.erase(system.constraints.begin() + i);
}

/// Adds w(x) = height on @p wire as a bilateral constraint; returns its index.
unsigned int hold(SemiDiscreteSystem& system, const CatenaryDiscretisation& space,
                  Wire wire, double x, double height, const std::string& name)
{
  system.add_constraint(
      std::make_unique<FixedConstraint>(name, Constraint::Kind::bilateral,
                                        wire_point_row(space, system, wire, x), -height));
  return system.n_constraints() - 1;
}

/// True if the scene has steady arms (SteadyArms).
bool has_steady_arms(const SceneParameters& scene, const CatenaryParameters& c)
{
  return SteadyArms().enabled(scene, c);
}

/// True if the scene holds the carrier on springs (CarrierSupports, spring).
bool has_carrier_springs(const SceneParameters& scene, const CatenaryParameters& c)
{
  return CarrierSupports().enabled(scene, c) &&
         c.carrier_support == CarrierSupport::spring;
}

/// The static catenary of @p c with every support held fixed, and the indices
/// of the steady-arm and carrier-spring holds (their multipliers are the preloads).
struct HeldCatenary
{
  SemiDiscreteSystem system;
  std::vector<unsigned int> steady_arms, carrier_springs, heights;
};

/// Marks a dropper without a height hold (released: at zero force).
constexpr unsigned int no_hold = static_cast<unsigned int>(-1);

HeldCatenary held_catenary(const SceneParameters& scene, const CatenaryParameters& c,
                           const CatenaryDiscretisation& space, const bool heights,
                           const std::vector<bool>& released)
{
  BuiltScene built = build_catenary(scene, c, space);
  HeldCatenary h{std::move(built.catenary_only), {}, {}, {}};
  if (heights)
    remove_constraints(h.system, built.dropper_indices);
  const std::vector<double> arms = c.steady_arm_positions();
  for (unsigned int k = 0; k < arms.size() && has_steady_arms(scene, c); ++k)
    h.steady_arms.push_back(hold(h.system, space, Wire::contact_wire, arms[k], 0.,
                                 "steady arm " + std::to_string(k + 1)));
  const std::vector<double> supports = c.interior_supports();
  for (unsigned int k = 0; k < supports.size() && has_carrier_springs(scene, c); ++k)
    h.carrier_springs.push_back(hold(h.system, space, Wire::carrier, supports[k], 0.,
                                     "carrier support " + std::to_string(k + 1)));
  const std::vector<double> z =
      heights ? c.dropper_target_displacements() : std::vector<double>();
  for (unsigned int j = 0; j < z.size(); ++j)
    h.heights.push_back(released[j] ? no_hold
                                    : hold(h.system, space, Wire::contact_wire,
                                           c.dropper_positions[j], z[j],
                                           "height at dropper " + std::to_string(j + 1)));
  return h;
}

/// The entry that set the design's target at a dropper, for a refusal: its
/// name, its value, the targets in words and which way they can be produced.
struct TargetEntry
{
  std::string parameter, value, targets, producible;
};

TargetEntry target_entry(const CatenaryParameters& c, const unsigned int j)
{
  if (c.target_heights.empty())
    return {"Catenary/Droppers/Pre-sag", number_to_string(c.presag), "a pre-sag",
            "smaller"};
  return {"Catenary/Droppers/Target heights",
          number_to_string(c.target_heights[j]) + " (dropper " + std::to_string(j + 1) +
              ")",
          "targets", "lower"};
}

/// Refuses the target at dropper @p j when the design gives it a @p length <= 0
/// or a @p force <= 0 (the dropper would have to push).
void check_designed_dropper(const CatenaryParameters& c, const unsigned int j,
                            const double length, const double force)
{
  if (length > 0. && force > 0.) // the messages only when they fail: O(n) in all
    return;
  const TargetEntry e = target_entry(c, j);
  const std::string dropper = "dropper " + std::to_string(j + 1) +
                              " at x = " + number_to_string(c.dropper_positions[j]) +
                              " m";
  require(length > 0., e.parameter, e.value,
          "the design gives " + dropper + " the length " + number_to_string(length) +
              " m; allowed: " + e.targets + " the droppers can produce (" + e.producible +
              ", or a larger Encumbrance)");
  require(false, e.parameter, e.value,
          "the design needs " + dropper + " to push (" + number_to_string(force) +
              " N); allowed: " + e.targets + " the droppers can hold in tension");
}

/**
 * Step 3 of the design: l_j = w_c(x_j) - z_j (less F_j / k_d for an elastic
 * dropper), w_c the height of the wire dropper j hangs from in the static
 * state @p s (the carrier or its stitch wire), z_j its target (@p z); sets
 * them in @p c and returns the largest change of a length.
 */
double update_lengths(const SceneParameters& scene, CatenaryParameters& c,
                      const CatenaryDiscretisation& space,
                      const SemiDiscreteSystem& system, const StaticEquilibrium& s,
                      const std::vector<double>& z, const std::vector<double>& forces,
                      const std::vector<bool>& released)
{
  double change = 0.;
  for (unsigned int j = 0; j < c.n_droppers(); ++j)
  {
    // The height of the dropper's upper clamp: the carrier, or its stitch wire.
    const double carrier =
        c.support_height + dropper_upper_row(space, system, j).dot(s.q);
    // An elastic dropper stretches by F_j / k_d under its tension F_j: its
    // unstretched length is the distance less the stretch.
    const double stretch =
        scene.droppers == DropperModel::elastic ? forces[j] / c.dropper_stiffness : 0.;
    const double length = carrier - z[j] - stretch;
    if (!released[j]) // a released dropper holds nothing
      check_designed_dropper(c, j, length, forces[j]);
    change = std::max(change, std::abs(length - c.dropper_lengths[j]));
    c.dropper_lengths[j] = length;
  }
  return change;
}

/// The change of the load by the dropper weights since the lengths were @p l0
/// (add_dropper_weight_change(): the held catenary keeps the load of l0).
dealii::Vector<double> weight_change_since(const SceneParameters& scene,
                                           const CatenaryParameters& c,
                                           const CatenaryDiscretisation& space,
                                           const SemiDiscreteSystem& system,
                                           const std::vector<double>& l0)
{
  dealii::Vector<double> weights(system.n_dofs());
  std::vector<double> length_changes(c.n_droppers());
  for (unsigned int j = 0; j < c.n_droppers(); ++j)
    length_changes[j] = c.dropper_lengths[j] - l0[j];
  add_dropper_weight_change(scene, c, space, system, length_changes, weights);
  return weights;
}

std::vector<double> multipliers_of(const StaticEquilibrium& s,
                                   const std::vector<unsigned int>& indices)
{
  std::vector<double> m;
  for (const unsigned int i : indices)
    m.push_back(i == no_hold ? 0. : s.multipliers[i]);
  return m;
}

/**
 * Releases the droppers whose held target needs a push (@p forces < 0), if
 * the section lets the design release them; true if it released one.
 */
bool release_pushing_droppers(const CatenaryParameters& c,
                              const std::vector<double>& forces,
                              std::vector<bool>& released)
{
  if (!c.release_unreachable_targets)
    return false;
  bool any = false;
  for (unsigned int j = 0; j < forces.size(); ++j)
    if (!released[j] && forces[j] < 0.)
      released[j] = any = true;
  return any;
}

/// The targets @p z with the released droppers' replaced by where the wire
/// is in the static state @p s (their droppers hold nothing).
std::vector<double> reached_targets(const CatenaryParameters& c,
                                    const CatenaryDiscretisation& space,
                                    const SemiDiscreteSystem& system,
                                    const StaticEquilibrium& s, std::vector<double> z,
                                    const std::vector<bool>& released)
{
  for (unsigned int j = 0; j < z.size(); ++j)
    if (released[j])
      z[j] = wire_point_row(space, system, Wire::contact_wire, c.dropper_positions[j])
                 .dot(s.q);
  return z;
}
} // namespace

bool needs_design(const SceneParameters& scene, const CatenaryParameters& catenary)
{
  return (catenary.design == DropperDesign::designed && scene.has_droppers()) ||
         has_steady_arms(scene, catenary) || has_carrier_springs(scene, catenary);
}

namespace
{
/// How one fixed-point iteration of the design ended.
enum class DesignPass
{
  converged,
  released ///< a dropper was released: the iteration starts again
};

/**
 * The fixed-point iteration of design_catenary() with the droppers of
 * @p released at zero force; releases more (and stops) if a held target needs
 * a push and the section allows it.
 */
DesignPass design_pass(const SceneParameters& scene, const CatenaryDiscretisation& space,
                       const double column_budget, const bool designing,
                       std::vector<bool>& released, CatenaryDesignResult& r)
{
  CatenaryParameters& c = r.catenary;
  std::vector<double> steady_arm_preloads, carrier_support_preloads;
  // The held catenary is built and factorised once, with the lengths it
  // starts from (l0); only the dropper weights depend on the lengths, and
  // they enter each iteration as a change of the load.
  const HeldCatenary h = held_catenary(scene, c, space, designing, released);
  const StaticEquilibriumSolver solver(h.system, 0., column_budget);
  const std::vector<double> l0 = c.dropper_lengths;
  const std::vector<double> z =
      designing ? c.dropper_target_displacements() : std::vector<double>();
  double previous_change = std::numeric_limits<double>::infinity();
  for (unsigned int it = 0; it < 50; ++it)
  {
    r.iterations = it + 1;
    const dealii::Vector<double> weights =
        weight_change_since(scene, c, space, h.system, l0);
    StaticEquilibrium s = solver.solve(weights);
    if (!designing)
    {
      c.steady_arm_preloads = multipliers_of(s, h.steady_arms);
      c.carrier_support_preloads = multipliers_of(s, h.carrier_springs);
      return DesignPass::converged;
    }
    // Step 2: the droppers' tensions pull the carrier down.
    r.dropper_forces = multipliers_of(s, h.heights);
    if (release_pushing_droppers(c, r.dropper_forces, released))
    {
      c.dropper_lengths = l0;
      return DesignPass::released;
    }
    const std::vector<double> reached =
        reached_targets(c, space, h.system, s, z, released);
    dealii::Vector<double> pull = weights;
    for (unsigned int j = 0; j < c.n_droppers(); ++j)
      dropper_upper_row(space, h.system, j).add_transpose_to(pull, -r.dropper_forces[j]);
    s = solver.solve(pull);
    steady_arm_preloads = multipliers_of(s, h.steady_arms);
    carrier_support_preloads = multipliers_of(s, h.carrier_springs);
    const double change =
        update_lengths(scene, c, space, h.system, s, reached, r.dropper_forces, released);
    // Converged: the lengths move by less than 1e-10 m, or they have reached the
    // round-off of the static solves (the iteration contracts by about 1/250
    // per step; with Hermite elements at h = 0.125 m the solves' round-off
    // leaves changes of 2e-10 to 6e-10 m that no longer shrink): a change
    // below 10 nm that did not halve.
    const bool at_round_off = change < 1e-8 && change > 0.5 * previous_change;
    previous_change = change;
    if (change < 1e-10 || at_round_off)
    {
      c.steady_arm_preloads = steady_arm_preloads;
      c.carrier_support_preloads = carrier_support_preloads;
      return DesignPass::converged;
    }
  }
  throw SimulationError("the dropper design did not converge in 50 iterations");
}
} // namespace

CatenaryDesignResult design_catenary(const SceneParameters& scene,
                                     const CatenaryParameters& catenary,
                                     const CatenaryDiscretisation& space,
                                     const double column_budget)
{
  CatenaryDesignResult r{catenary, {}, 0, {}};
  CatenaryParameters& c = r.catenary;
  // The holds carry the preloads during the design: the catenary is built
  // without them, and they are set once, at the end.
  c.steady_arm_preloads.clear();
  c.carrier_support_preloads.clear();
  const bool designing =
      catenary.design == DropperDesign::designed && scene.has_droppers();
  std::vector<bool> released(c.n_droppers(), false);
  while (design_pass(scene, space, column_budget, designing, released, r) ==
         DesignPass::released)
    continue;
  for (unsigned int j = 0; j < released.size(); ++j)
    if (released[j])
      r.released.push_back(j);
  return r;
}
} // namespace pantocat
