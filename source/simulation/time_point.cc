#include <pantocat/simulation/time_point.h>

#include <algorithm>

namespace pantocat
{
double contact_force(const PantographLayout& p, const TimePoint& point)
{
  double sum = 0.;
  for (const unsigned int i : p.wire_contacts)
    sum += point.lambda[i];
  return sum;
}

bool in_contact(const PantographLayout& p, const TimePoint& point)
{
  for (const unsigned int i : p.wire_contacts)
    if (point.active[i])
      return true;
  return false;
}

bool SimulationLayout::has_contact() const
{
  return !contacts().empty();
}

const PantographLayout* SimulationLayout::contact_owner(const unsigned int i) const
{
  for (const PantographLayout& p : pantographs)
    if (std::find(p.wire_contacts.begin(), p.wire_contacts.end(), i) !=
        p.wire_contacts.end())
      return &p;
  return nullptr;
}

std::vector<const PantographLayout*> SimulationLayout::contacts() const
{
  std::vector<const PantographLayout*> list;
  for (const PantographLayout& p : pantographs)
    if (p.has_contact())
      list.push_back(&p);
  return list;
}
} // namespace pantocat
