#include <pantocat/base/number_format.h>
#include <pantocat/scene/stitch_wires.h>

namespace pantocat
{
std::string StitchWires::name() const
{
  return "stitch wires";
}

bool StitchWires::enabled(const SceneParameters&,
                          const CatenaryParameters& catenary) const
{
  return !catenary.stitch_wires.empty();
}

void StitchWires::add_bodies(SceneAssembly& a) const
{
  BlockOperator op;
  a.space().stitch_wires().initialize_operator(op);
  op.name = a.space().stitch_block_name();
  a.bodies.push_back(std::move(op));
}

void StitchWires::add_terms(SceneAssembly& a) const
{
  const CatenaryParameters& c = a.catenary();
  const SceneParameters& scene = a.scene;
  BlockOperator& op = *a.stitch_body();
  const bool viscous = scene.damping && c.damping == CatenaryDamping::viscous;
  const bool clamp_weights = scene.clamp_and_dropper_masses && scene.gravity;
  for (unsigned int i = 0; i < c.stitch_wires.size(); ++i)
  {
    const StitchWire& s = c.stitch_wires[i];
    WireTerms terms;
    terms.mass = s.mass_per_length;
    terms.tension = s.tension;
    terms.damping = viscous ? s.damping : 0.;
    terms.weight = scene.gravity ? s.mass_per_length * c.gravity : 0.;
    a.space().stitch_wires().add_terms(i, terms, op);
    for (const double x : {s.start(), s.end()})
    {
      if (clamp_weights)
        a.add_point_force(Wire::carrier, x, -s.clamp_mass * c.gravity);
      if (clamp_weights && c.point_mass_inertia)
        a.add_point_mass(Wire::carrier, x, s.clamp_mass);
    }
  }
}

void StitchWires::add_constraints(SceneAssembly& a) const
{
  const CatenaryParameters& c = a.catenary();
  for (unsigned int i = 0; i < c.stitch_wires.size(); ++i)
  {
    const StitchWire& s = c.stitch_wires[i];
    const double ends[2] = {s.start(), s.end()};
    for (unsigned int e = 0; e < 2; ++e)
    {
      // u_s(x) - u_c(x) = 0: both measured from l_c.
      SparseRow row = stitch_wire_point_row(a.space(), a.system, i, ends[e]);
      const SparseRow carrier = a.wire_row(Wire::carrier, ends[e]);
      for (std::size_t k = 0; k < carrier.size(); ++k)
        row.add(carrier.index[k], -carrier.value[k]);
      a.system.add_constraint(std::make_unique<FixedConstraint>(
          a.constraint_name("stitch wire " + std::to_string(i + 1) + " clamp " +
                            std::to_string(e + 1)),
          Constraint::Kind::bilateral, row, 0.));
    }
  }
}

std::string StitchWires::describe(const SceneAssembly& a) const
{
  const CatenaryParameters& c = a.catenary();
  unsigned int droppers = 0;
  for (const StitchWire& s : c.stitch_wires)
    droppers += s.droppers.size();
  return std::to_string(c.stitch_wires.size()) +
         " stitch wires: strings clamped to the " + "carrier at both ends, " +
         std::to_string(a.space().stitch_wires().n_dofs()) + " unknowns, " +
         std::to_string(droppers) + " droppers hang from them";
}
} // namespace pantocat
