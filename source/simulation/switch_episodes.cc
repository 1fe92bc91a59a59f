#include <pantocat/simulation/switch_episodes.h>

namespace pantocat
{
std::vector<SwitchEpisode> switch_episodes(const std::vector<Interval>& open,
                                           const double gap)
{
  std::vector<SwitchEpisode> list;
  for (const Interval& i : open)
  {
    if (list.empty() || i.first - list.back().span.second >= gap)
      list.push_back({i, 0, 0.});
    SwitchEpisode& e = list.back();
    e.span.second = i.second;
    ++e.intervals;
    e.open_time += i.second - i.first;
  }
  return list;
}
} // namespace pantocat
