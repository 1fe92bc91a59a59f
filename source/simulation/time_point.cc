#include <pantocat/simulation/time_point.h>

namespace pantocat
{
bool SimulationLayout::has_contact() const
{
  return !contacts().empty();
}

const PantographLayout* SimulationLayout::contact_owner(const unsigned int i) const
{
  for (const PantographLayout& p : pantographs)
    if (p.contact == i)
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
