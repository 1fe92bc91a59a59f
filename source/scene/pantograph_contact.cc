#include <pantocat/scene/pantograph_contact.h>

namespace pantocat
{
std::string PantographContact::name() const
{
  return "contact";
}

bool PantographContact::enabled(const SceneParameters& scene) const
{
  return scene.has_pantograph_body();
}

void PantographContact::add_constraints(SceneAssembly& a) const
{
  SemiDiscreteSystem& s = a.system;
  const unsigned int pantograph = s.block("pantograph").first;
  a.contact_index = s.n_constraints();
  if (s.has_block("contact wire"))
  {
    s.add_constraint(std::make_unique<ContactConstraint>(
        a.space, *a.pantograph, s.block("contact wire").first, pantograph, a.motion,
        a.scene.contact));
    return;
  }
  // A rigid wire at height 0: Delta_p = 0 - b(q_MBS) = -B q_MBS.
  SparseRow row = a.pantograph->head_row();
  row.shift(pantograph);
  for (double& b : row.value)
    b = -b;
  s.add_constraint(
      std::make_unique<FixedConstraint>("contact", a.scene.contact, row, 0.));
}

std::string PantographContact::describe(const SceneAssembly& a) const
{
  return std::string("contact: ") +
         (a.scene.contact == Constraint::Kind::bilateral ? "bilateral" : "unilateral") +
         (a.scene.contact_wire == WireModel::rigid ? " on a rigid wire"
                                                   : " (32), " + a.load_shape());
}
} // namespace pantocat
