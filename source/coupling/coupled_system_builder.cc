#include <pantocat/coupling/coupled_system_builder.h>
#include <pantocat/system/catenary_system_builder.h>

namespace pantocat
{
CoupledSystem build_coupled_system(const CatenaryDiscretisation& discretisation,
                                   const PantographModel& pantograph,
                                   const ContactPointMotion& motion,
                                   const Constraint::Kind dropper_kind,
                                   const Constraint::Kind contact_kind)
{
  CoupledSystem s;
  s.catenary_only = build_catenary_system(discretisation, dropper_kind);
  BlockOperator pantograph_operator;
  pantograph.assemble(pantograph_operator);
  s.coupled = build_catenary_system(discretisation, dropper_kind, {&pantograph_operator});
  auto contact = std::make_unique<ContactConstraint>(
      discretisation, pantograph, s.coupled.block("contact wire").first,
      s.coupled.block("pantograph").first, motion, contact_kind);
  s.contact = contact.get();
  s.contact_index = s.coupled.n_constraints();
  s.coupled.add_constraint(std::move(contact));
  return s;
}
} // namespace pantocat
