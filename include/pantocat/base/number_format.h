#pragma once

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

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

/// "a, b, c": a list as a prm file gives it (number_to_string() of each), for
/// messages that name the value.
template <typename Number>
std::string list_to_string(const std::vector<Number>& values)
{
  std::string text;
  for (const Number x : values)
    text += (text.empty() ? "" : ", ") + number_to_string(static_cast<double>(x));
  return text;
}

/// A CSV field of a study table: @p value to 7 significant digits, empty if
/// it is not finite (no run, no difference).
inline std::string csv_field(const double value)
{
  return std::isfinite(value) ? number_to_string(value, 7) : std::string();
}
} // namespace pantocat
