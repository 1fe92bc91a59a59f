#include <pantocat/base/number_format.h>
#include <pantocat/coupling/contact_constraint.h>
#include <pantocat/scene/pantograph_contact.h>

namespace pantocat
{
std::string PantographContact::name() const
{
  return "contact";
}

bool PantographContact::enabled(const SceneParameters& scene,
                                const CatenaryParameters&) const
{
  return scene.has_pantograph_body();
}

void PantographContact::add_constraints(SceneAssembly& a) const
{
  SemiDiscreteSystem& s = a.system;
  for (ScenePantograph& p : a.pantographs)
  {
    if (!p.model)
      continue;
    SparseRow head = p.model->head_row();
    head.shift(s.block(p.block).first);
    p.contact_index = s.n_constraints();
    const Constraint::Kind kind = p.data->contact;
    if (s.has_block("contact wire"))
    {
      s.add_constraint(std::make_unique<ContactConstraint>(
          p.contact, WirePointMarker(a.space, s.block("contact wire").first, p.motion),
          head, kind, p.data->contact_compliance));
      continue;
    }
    // A rigid wire at height 0: Delta_p = 0 - b(q_MBS) = -B q_MBS.
    for (double& b : head.value)
      b = -b;
    s.add_constraint(std::make_unique<FixedConstraint>(p.contact, kind, head, 0.,
                                                       p.data->contact_compliance));
  }
}

std::string PantographContact::describe(const SceneAssembly& a) const
{
  std::string line;
  for (const ScenePantograph& p : a.pantographs)
    if (p.model)
      line += (line.empty() ? "" : "; ") + p.contact + ": " +
              (p.data->contact_compliance.stiffness > 0.
                   ? "penalty, k_c = " +
                         number_to_string(p.data->contact_compliance.stiffness) + " N/m"
                   : p.data->contact_law()) +
              (a.scene.contact_wire == WireModel::rigid ? " on a rigid wire"
                                                        : " (32), " + a.load_shape());
  return line;
}
} // namespace pantocat
