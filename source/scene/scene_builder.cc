#include <pantocat/scene/carrier_body.h>
#include <pantocat/scene/carrier_supports.h>
#include <pantocat/scene/clamp_and_dropper_masses.h>
#include <pantocat/scene/contact_wire_body.h>
#include <pantocat/scene/droppers.h>
#include <pantocat/scene/gravity.h>
#include <pantocat/scene/moving_force.h>
#include <pantocat/scene/pantograph_body.h>
#include <pantocat/scene/pantograph_contact.h>
#include <pantocat/scene/rayleigh_damping.h>
#include <pantocat/scene/scene_builder.h>
#include <pantocat/scene/steady_arms.h>
#include <pantocat/scene/stitch_wires.h>
#include <pantocat/scene/viscous_damping.h>
#include <pantocat/scene/wire_bending.h>
#include <pantocat/scene/wire_tension.h>

#include <algorithm>
#include <stdexcept>

namespace pantocat
{
std::vector<std::unique_ptr<SceneEffect>> registered_scene_effects()
{
  std::vector<std::unique_ptr<SceneEffect>> e;
  e.push_back(std::make_unique<CarrierBody>());
  e.push_back(std::make_unique<ContactWireBody>());
  // Before the pantographs: the catenary's unknowns come first.
  e.push_back(std::make_unique<StitchWires>());
  e.push_back(std::make_unique<PantographBody>());
  e.push_back(std::make_unique<WireTension>());
  e.push_back(std::make_unique<WireBending>());
  e.push_back(std::make_unique<Gravity>());
  e.push_back(std::make_unique<ViscousDamping>());
  e.push_back(std::make_unique<ClampAndDropperMasses>());
  e.push_back(std::make_unique<SteadyArms>());
  e.push_back(std::make_unique<CarrierSupports>());
  // After every effect that adds to the wires' M or K.
  e.push_back(std::make_unique<RayleighDamping>());
  e.push_back(std::make_unique<Droppers>());
  e.push_back(std::make_unique<PantographContact>());
  e.push_back(std::make_unique<MovingForce>());
  return e;
}

namespace
{
/// The enabled effects: the catenary's per section, and the pantographs'.
struct EnabledEffects
{
  std::vector<std::vector<const SceneEffect*>> per_section;
  std::vector<const SceneEffect*> pantographs;
  std::vector<std::string> inactive;
};

/**
 * Runs the three phases: in each, the catenary's effects on every section in
 * turn (its unknowns and constraints together, section after section), then
 * the pantographs' effects (with @p with_pantographs) on the whole line.
 */
void assemble(SceneAssembly& a, const EnabledEffects& effects,
              const bool with_pantographs)
{
  const auto phase = [&](void (SceneEffect::*add)(SceneAssembly&) const)
  {
    for (unsigned int k = 0; k < a.sections.size(); ++k)
    {
      a.select_section(k);
      for (const SceneEffect* e : effects.per_section[k])
        (e->*add)(a);
    }
    a.select_section(0);
    for (const SceneEffect* e : effects.pantographs)
      if (with_pantographs)
        (e->*add)(a);
  };
  phase(&SceneEffect::add_bodies);
  phase(&SceneEffect::add_terms);
  std::vector<const BlockOperator*> bodies;
  for (const BlockOperator& b : a.bodies)
    bodies.push_back(&b);
  a.system.set_blocks(bodies);
  phase(&SceneEffect::add_constraints);
}
} // namespace

bool BuiltScene::has_contact() const
{
  for (const ScenePantograph& p : pantographs)
    if (p.has_contact())
      return true;
  return false;
}

namespace
{
EnabledEffects
enabled_effects(const std::vector<std::unique_ptr<SceneEffect>>& registered,
                const SceneParameters& scene, const std::vector<SceneSection>& sections)
{
  EnabledEffects e;
  e.per_section.resize(sections.size());
  for (const auto& effect : registered)
  {
    bool anywhere = false;
    for (unsigned int k = 0; k < sections.size(); ++k)
    {
      const bool on = effect->enabled(scene, *sections[k].catenary);
      anywhere = anywhere || on;
      if (on && effect->part_of_catenary())
        e.per_section[k].push_back(effect.get());
    }
    if (!anywhere)
      e.inactive.push_back(effect->name());
    else if (!effect->part_of_catenary())
      e.pantographs.push_back(effect.get());
  }
  return e;
}

/**
 * One line per active effect: the catenary's as section 1 describes them
 * ("(in each of the k sections)" when every section says the same, else one
 * line per section), then the pantographs'.
 */
std::vector<std::string> describe(SceneAssembly& a, const EnabledEffects& effects)
{
  std::vector<std::string> lines;
  const unsigned int n = a.sections.size();
  for (const SceneEffect* e : effects.per_section.front())
  {
    std::vector<std::string> by_section;
    for (unsigned int k = 0; k < n; ++k)
    {
      a.select_section(k);
      by_section.push_back(e->describe(a));
    }
    if (std::all_of(by_section.begin(), by_section.end(),
                    [&](const std::string& d) { return d == by_section.front(); }))
      lines.push_back(
          by_section.front() +
          (n > 1 ? " (in each of the " + std::to_string(n) + " sections)" : ""));
    else
      for (unsigned int k = 0; k < n; ++k)
        lines.push_back(a.sections[k].catenary->name + ": " + by_section[k]);
  }
  a.select_section(0);
  for (const SceneEffect* e : effects.pantographs)
    lines.push_back(e->describe(a));
  return lines;
}

std::vector<SceneSection> one_section(const CatenaryParameters& catenary,
                                      const CatenaryDiscretisation& space)
{
  return {SceneSection{&catenary, &space}};
}
} // namespace

BuiltScene build_scene(const SceneParameters& scene,
                       const std::vector<SceneSection>& sections)
{
  const auto registered = registered_scene_effects();
  const EnabledEffects effects = enabled_effects(registered, scene, sections);
  BuiltScene built;
  built.inactive_effects = effects.inactive;

  const std::vector<ScenePantograph> pantographs = make_scene_pantographs(scene);
  SceneAssembly whole(scene, sections, pantographs);
  assemble(whole, effects, true);
  SceneAssembly static_part(scene, sections, pantographs);
  assemble(static_part, effects, false);

  built.active_effects = describe(whole, effects);
  built.system = std::move(whole.system);
  built.catenary_only = std::move(static_part.system);
  built.pantographs = std::move(whole.pantographs);
  built.dropper_indices = whole.dropper_indices;
  built.support_indices = whole.support_indices;
  return built;
}

BuiltScene build_scene(const SceneParameters& scene, const CatenaryParameters& catenary,
                       const CatenaryDiscretisation& space)
{
  return build_scene(scene, one_section(catenary, space));
}

BuiltScene build_catenary(const SceneParameters& scene,
                          const CatenaryParameters& catenary,
                          const CatenaryDiscretisation& space)
{
  const auto registered = registered_scene_effects();
  const std::vector<SceneSection> sections = one_section(catenary, space);
  const EnabledEffects effects = enabled_effects(registered, scene, sections);
  SceneAssembly part(scene, sections, make_scene_pantographs(scene));
  assemble(part, effects, false);
  BuiltScene built;
  built.catenary_only = std::move(part.system);
  built.dropper_indices = part.dropper_indices;
  built.support_indices = part.support_indices;
  return built;
}
} // namespace pantocat
