#pragma once

#include <vector>

namespace pantocat
{
/// Rows [first, last) of a matrix whose coefficients are those of row first
/// (even distance) or first + 1 (odd distance), but for the rows `exceptions`.
struct RepeatingRows
{
  int first = 0, last = 0;
  std::vector<int> exceptions;
};

/**
 * The runs of rows of [@p begin, @p end) that repeat with period 2 (a
 * uniform Hermite beam's value and slope rows; period 1 is a special case),
 * as DiagonalForceSweep and PatternOperators keep coefficients aside for.
 *
 * A run takes the coefficients of its first two rows; rows with others (a
 * point mass, a support) are its exceptions. The scan of a run ends where
 * more than 8 exceptions follow each other (the run ends at its last row
 * with the pattern), where they become more than one in eight, or at a row
 * for which @p fits is false. A run is kept if it has at least @p minimum
 * rows and at most one in four exceptions, which every scan longer than
 * @p minimum + 8 meets: a start without a run costs O(@p minimum), and the
 * scans stay linear in the number of rows.
 *
 * @p opens(s): rows s and s + 1 may open a run (it may prepare what @p fits
 * reads); @p fits(i): row i may belong to the run opened last; @p same(i, j):
 * rows i and j have the same coefficients.
 */
template <typename Opens, typename Fits, typename Same>
std::vector<RepeatingRows> find_repeating_rows(const int begin, const int end,
                                               const int minimum, const Opens& opens,
                                               const Fits& fits, const Same& same)
{
  constexpr int gap_limit = 8;
  std::vector<RepeatingRows> found;
  std::vector<int> own;
  int start = begin;
  while (start + minimum <= end)
  {
    if (!opens(start))
    {
      ++start;
      continue;
    }
    int last_match = start + 1, gap = 0;
    own.clear();
    for (int i = start + 2; i < end && gap <= gap_limit && fits(i); ++i)
    {
      if (same(i, start + (i - start) % 2))
        last_match = i, gap = 0;
      else
      {
        ++gap;
        own.push_back(i);
      }
      if (i - start >= minimum && 8 * static_cast<int>(own.size()) > i - start)
        break;
    }
    const int last = last_match + 1;
    while (!own.empty() && own.back() >= last) // the rows after the last match
      own.pop_back();
    if (last - start < minimum || 4 * static_cast<int>(own.size()) > last - start)
    {
      ++start;
      continue;
    }
    found.push_back({start, last, own});
    start = last;
  }
  return found;
}
} // namespace pantocat
