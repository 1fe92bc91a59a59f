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
/// Runs the three phases of the effects in @p effects.
void assemble(SceneAssembly& a, const std::vector<const SceneEffect*>& effects)
{
  for (const SceneEffect* e : effects)
    e->add_bodies(a);
  for (const SceneEffect* e : effects)
    e->add_terms(a);
  std::vector<const BlockOperator*> bodies;
  for (const BlockOperator& b : a.bodies)
    bodies.push_back(&b);
  a.system.set_blocks(bodies);
  for (const SceneEffect* e : effects)
    e->add_constraints(a);
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
/// The enabled effects of @p registered, all and the catenary's part.
struct EnabledEffects
{
  std::vector<const SceneEffect*> all, catenary_part;
  std::vector<std::string> inactive;
};

EnabledEffects
enabled_effects(const std::vector<std::unique_ptr<SceneEffect>>& registered,
                const SceneParameters& scene, const CatenaryParameters& catenary)
{
  EnabledEffects e;
  for (const auto& effect : registered)
  {
    if (!effect->enabled(scene, catenary))
    {
      e.inactive.push_back(effect->name());
      continue;
    }
    e.all.push_back(effect.get());
    if (effect->part_of_catenary())
      e.catenary_part.push_back(effect.get());
  }
  return e;
}
} // namespace

BuiltScene build_scene(const SceneParameters& scene, const CatenaryParameters& catenary,
                       const CatenaryDiscretisation& space)
{
  const auto registered = registered_scene_effects();
  const EnabledEffects effects = enabled_effects(registered, scene, catenary);
  const std::vector<const SceneEffect*>&all = effects.all,
                          &catenary_part = effects.catenary_part;
  BuiltScene built;
  built.inactive_effects = effects.inactive;

  const std::vector<ScenePantograph> pantographs = make_scene_pantographs(scene);
  SceneAssembly whole(scene, catenary, space, pantographs);
  assemble(whole, all);
  SceneAssembly static_part(scene, catenary, space, pantographs);
  assemble(static_part, catenary_part);

  for (const SceneEffect* e : all)
    built.active_effects.push_back(e->describe(whole));
  built.system = std::move(whole.system);
  built.catenary_only = std::move(static_part.system);
  built.pantographs = std::move(whole.pantographs);
  built.dropper_indices = whole.dropper_indices;
  built.support_indices = whole.support_indices;
  return built;
}

BuiltScene build_catenary(const SceneParameters& scene,
                          const CatenaryParameters& catenary,
                          const CatenaryDiscretisation& space)
{
  const auto registered = registered_scene_effects();
  const EnabledEffects effects = enabled_effects(registered, scene, catenary);
  SceneAssembly part(scene, catenary, space, make_scene_pantographs(scene));
  assemble(part, effects.catenary_part);
  BuiltScene built;
  built.catenary_only = std::move(part.system);
  built.dropper_indices = part.dropper_indices;
  built.support_indices = part.support_indices;
  return built;
}
} // namespace pantocat
