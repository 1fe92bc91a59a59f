#include "compliant_benchmark.h"
#include <pantocat/simulation/initial_state.h>

namespace pantocat
{
namespace
{
/// Replaces the droppers of @p system (by name) by compliant ones.
void make_droppers_compliant(SemiDiscreteSystem& system, const Compliance& law)
{
  ConstraintState rows;
  for (auto& c : system.constraints)
    if (c->name().rfind("dropper ", 0) == 0)
    {
      c->evaluate(0., rows, 0);
      c = std::make_unique<FixedConstraint>(c->name(), c->kind(), rows.G, rows.z, law);
    }
}
} // namespace

BuiltCase build_case_with_compliant_droppers(const Case& c, const Compliance& droppers)
{
  BuiltCase b;
  b.space = create_catenary_discretisation(c.catenary, c.discretisation);
  b.built = build_scene(c.scene, c.catenary, *b.space);
  if (droppers.stiffness > 0.)
  {
    make_droppers_compliant(b.built.system, droppers);
    make_droppers_compliant(b.built.catenary_only, droppers);
  }
  std::vector<InitialContact> contacts;
  for (const ScenePantograph& p : b.built.pantographs)
    if (p.has_contact())
      contacts.push_back({p.model.get(), p.contact_index, p.block,
                          p.data->parameters.initial_contact_force,
                          p.data->parameters.initial_offset});
  b.initial = consistent_initial_state(b.built.catenary_only, b.built.system, contacts);
  return b;
}
} // namespace pantocat
