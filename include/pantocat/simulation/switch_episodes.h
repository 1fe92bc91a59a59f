#pragma once

#include <pantocat/simulation/run_statistics.h>

#include <vector>

namespace pantocat
{
/**
 * An episode of a unilateral constraint: its open intervals (contact lost,
 * dropper slack) with every reclosure between them shorter than the episode
 * gap (Statistics/Episode resolution), merged. Where a dropper and the contact act
 * on one wire point, each rigid impact (Sec. 5.3) may open the other
 * constraint, and the cascade of ever shorter intervals is resolved event by
 * event: a finer step resolves more of it. The cascade's extent converges
 * under step refinement while the count of its intervals does not, so the
 * episodes are what event lists compare; the intervals are kept in them.
 */
struct SwitchEpisode
{
  Interval span; ///< first opening, last reclosure (or the end of the run) [s]
  unsigned int intervals = 0; ///< open intervals merged
  double open_time = 0.;      ///< the sum of their lengths [s] (<= the span's length)
};

/**
 * The episodes of one constraint from its open intervals @p open (in time
 * order): successive intervals whose reclosure, start of the next minus end
 * of the one before, is shorter than @p gap [s] are merged. gap = 0: every
 * interval is its own episode.
 */
std::vector<SwitchEpisode> switch_episodes(const std::vector<Interval>& open, double gap);
} // namespace pantocat
