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
/**
 * Both wires' reference is the support chord (CatenaryParameters::
 * support_chord()): where it changes slope by kappa at a support, the tension
 * T pulls the wire there by T kappa (upward for a chord bent upward), a point
 * load that the steady arm or the messenger's support carries.
 */
void add_chord_kinks(SceneAssembly& a, const Wire wire, const double tension)
{
  const CatenaryParameters& c = a.catenary();
  if (c.support_heights.empty())
    return;
  const std::vector<double> kinks = c.support_chord_kinks(), x = c.support_positions();
  for (unsigned int k = 1; k + 1 < x.size(); ++k)
    if (kinks[k] != 0.)
      a.add_point_force(wire, x[k], tension * kinks[k]);
}
} // namespace

std::string WireTension::name() const
{
  return "tension";
}

bool WireTension::enabled(const SceneParameters& scene, const CatenaryParameters&) const
{
  return carrier_tension(scene) || wire_tension(scene);
}

void WireTension::add_terms(SceneAssembly& a) const
{
  for (const Wire wire : {Wire::carrier, Wire::contact_wire})
    if (wire == Wire::carrier ? carrier_tension(a.scene) : wire_tension(a.scene))
    {
      WireTerms t;
      t.tension = a.wire_parameters(wire).tension;
      a.add_wire_terms(wire, t);
      add_chord_kinks(a, wire, t.tension);
    }
}

std::string WireTension::describe(const SceneAssembly& a) const
{
  std::string s = "tension:";
  if (carrier_tension(a.scene))
    s += " carrier T_c = " +
         std::to_string(static_cast<int>(a.catenary().carrier.tension)) + " N";
  if (wire_tension(a.scene))
    s += std::string(carrier_tension(a.scene) ? "," : "") + " contact wire T_w = " +
         std::to_string(static_cast<int>(a.catenary().contact_wire.tension)) + " N";
  return s;
}
} // namespace pantocat
