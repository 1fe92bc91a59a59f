#include <pantocat/scene/wire_tension.h>

namespace pantocat
{
namespace
{
bool carrier_tension(const SceneParameters& s)
{
  return s.carrier == WireModel::elastic && s.carrier_tension;
}
bool wire_tension(const SceneParameters& s)
{
  return s.contact_wire == WireModel::elastic && s.contact_wire_tension;
}
} // namespace

std::string WireTension::name() const
{
  return "tension";
}

bool WireTension::enabled(const SceneParameters& scene) const
{
  return carrier_tension(scene) || wire_tension(scene);
}

void WireTension::add_terms(SceneAssembly& a) const
{
  WireTerms t;
  if (carrier_tension(a.scene))
  {
    t.tension = a.catenary.carrier.tension;
    a.space.add_terms(Wire::carrier, t, *a.body("carrier"));
  }
  if (wire_tension(a.scene))
  {
    t.tension = a.catenary.contact_wire.tension;
    a.space.add_terms(Wire::contact_wire, t, *a.body("contact wire"));
  }
}

std::string WireTension::describe(const SceneAssembly& a) const
{
  std::string s = "tension:";
  if (carrier_tension(a.scene))
    s +=
        " carrier T_c = " + std::to_string(static_cast<int>(a.catenary.carrier.tension)) +
        " N";
  if (wire_tension(a.scene))
    s += std::string(carrier_tension(a.scene) ? "," : "") + " contact wire T_w = " +
         std::to_string(static_cast<int>(a.catenary.contact_wire.tension)) + " N";
  return s;
}
} // namespace pantocat
