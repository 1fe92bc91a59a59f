#include <pantocat/space/smoothed_delta.h>

namespace pantocat
{
SmoothedDelta::SmoothedDelta(const double epsilon) : eps(epsilon) {}
} // namespace pantocat
