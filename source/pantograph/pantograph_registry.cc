#include <pantocat/pantograph/mass_chain_pantograph.h>
#include <pantocat/pantograph/pantograph_registry.h>
#include <pantocat/pantograph/three_mass_pantograph.h>
#include <pantocat/pantograph/two_mass_pantograph.h>

namespace pantocat
{
const std::vector<PantographModelEntry>& registered_pantograph_models()
{
  static const std::vector<PantographModelEntry> entries{
      {"two-mass", [](const PantographParameters& p)
       { return std::make_unique<TwoMassPantograph>(p.two_mass); }},
      {"three-mass", [](const PantographParameters& p)
       { return std::make_unique<ThreeMassPantograph>(p.three_mass); }},
      {"mass-chain", [](const PantographParameters& p)
       { return std::make_unique<MassChainPantograph>(p.mass_chain, p.speed); }},
  };
  return entries;
}

const PantographModelEntry* find_pantograph_model(const std::string& name)
{
  for (const PantographModelEntry& e : registered_pantograph_models())
    if (e.name == name)
      return &e;
  return nullptr;
}

std::string pantograph_model_selection()
{
  std::string s;
  for (const PantographModelEntry& e : registered_pantograph_models())
    s += (s.empty() ? "" : "|") + e.name;
  return s;
}
} // namespace pantocat
