#pragma once

#include <sstream>
#include <stdexcept>
#include <string>

namespace pantocat
{
/**
 * A user error in the input: a parameter whose value is not allowed. The
 * message is one line that names the parameter, the value and what is allowed;
 * the program prints it and exits with a non-zero status before writing any
 * result.
 */
class InputError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};

/// Throws an InputError "<parameter> = <value>: <allowed>" unless @p condition holds.
template <typename Value>
void require(const bool condition, const std::string& parameter, const Value& value,
             const std::string& allowed)
{
  if (condition)
    return;
  std::ostringstream message;
  message << parameter << " = " << value << ": " << allowed;
  throw InputError(message.str());
}

/**
 * A run that cannot continue (a singular system, an instability, a cycling
 * active set): the message says where and why.
 */
class SimulationError : public std::runtime_error
{
public:
  using std::runtime_error::runtime_error;
};
} // namespace pantocat
