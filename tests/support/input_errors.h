#pragma once

#include <pantocat/base/input_error.h>

#include <string>

namespace pantocat
{
/// The message of the InputError that @p f throws ("" if none).
template <typename Function>
std::string input_error_of(const Function& f)
{
  try
  {
    f();
  }
  catch (const InputError& e)
  {
    return e.what();
  }
  return "";
}
} // namespace pantocat
