#include <pantocat/base/number_format.h>
#include <pantocat/scene/wire_bending.h>

namespace pantocat
{
namespace
{
bool carrier_bending(const SceneParameters& s)
{
  return s.carrier == WireModel::elastic && s.carrier_bending;
}
bool wire_bending(const SceneParameters& s)
{
  return s.contact_wire == WireModel::elastic && s.contact_wire_bending;
}
} // namespace

std::string WireBending::name() const
{
  return "bending";
}

bool WireBending::enabled(const SceneParameters& scene, const CatenaryParameters&) const
{
  return carrier_bending(scene) || wire_bending(scene);
}

void WireBending::add_terms(SceneAssembly& a) const
{
  for (const Wire wire : {Wire::carrier, Wire::contact_wire})
    if (wire == Wire::carrier ? carrier_bending(a.scene) : wire_bending(a.scene))
    {
      WireTerms t;
      t.bending = a.wire_parameters(wire).bending_stiffness;
      a.add_wire_terms(wire, t);
    }
}

std::string WireBending::describe(const SceneAssembly& a) const
{
  std::string s = "bending:";
  if (carrier_bending(a.scene))
    s += " carrier E I_c = " + number_to_string(a.catenary().carrier.bending_stiffness) +
         " N m^2";
  if (wire_bending(a.scene))
    s += std::string(carrier_bending(a.scene) ? "," : "") + " contact wire E I = " +
         number_to_string(a.catenary().contact_wire.bending_stiffness) + " N m^2";
  return s;
}
} // namespace pantocat
