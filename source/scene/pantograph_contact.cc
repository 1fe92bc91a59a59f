#include <pantocat/base/number_format.h>
#include <pantocat/coupling/contact_constraint.h>
#include <pantocat/scene/pantograph_contact.h>

#include <limits>

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

namespace
{
/**
 * The section whose contact wire the pantograph of @p motion touches at
 * t = 0: of the sections under x_p(0), the one whose wire hangs lowest.
 */
unsigned int section_at_start(const SceneAssembly& a, const ContactPointMotion& motion)
{
  const double x = motion.position(0.);
  unsigned int best = 0;
  double lowest = std::numeric_limits<double>::infinity();
  for (unsigned int k = 0; k < a.sections.size(); ++k)
  {
    const CatenaryParameters& c = *a.sections[k].catenary;
    const double local = x - c.start;
    if (local >= 0. && local <= c.length() && c.support_chord(local) < lowest)
      best = k, lowest = c.support_chord(local);
  }
  return best;
}

/// "contact", or "contact on section k" in a line of several sections.
std::string contact_name(const ScenePantograph& p, const CatenaryParameters& section)
{
  return section.name.empty() ? p.contact : p.contact + " on " + section.name;
}
} // namespace

void PantographContact::add_constraints(SceneAssembly& a) const
{
  SemiDiscreteSystem& s = a.system;
  const std::string wire = a.sections.front().space->wire_block_name(Wire::contact_wire);
  for (ScenePantograph& p : a.pantographs)
  {
    if (!p.model)
      continue;
    SparseRow head = p.model->head_row();
    head.shift(s.block(p.block).first);
    const Constraint::Kind kind = p.data->contact;
    if (s.has_block(wire))
    {
      // One contact per contact wire the head can touch: every section's.
      const unsigned int first = section_at_start(a, p.motion);
      for (const SceneSection& section : a.sections)
      {
        const CatenaryDiscretisation& space = *section.space;
        if (&section - a.sections.data() == first)
          p.contact_index = s.n_constraints();
        p.wire_contacts.push_back(s.n_constraints());
        s.add_constraint(std::make_unique<ContactConstraint>(
            contact_name(p, *section.catenary),
            WirePointMarker(space,
                            s.block(space.wire_block_name(Wire::contact_wire)).first,
                            p.motion),
            head, kind, p.data->contact_compliance));
      }
      continue;
    }
    p.contact_index = s.n_constraints();
    p.wire_contacts.push_back(s.n_constraints());
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
