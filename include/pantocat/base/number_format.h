#pragma once

#include <sstream>
#include <string>

namespace pantocat
{
/// Shortest round-trip text of a number ("15000", "0.03"), for parameter defaults and
/// CSV.
inline std::string number_to_string(const double value, const int digits = 15)
{
  std::ostringstream s;
  s.precision(digits);
  s << value;
  return s.str();
}
} // namespace pantocat
