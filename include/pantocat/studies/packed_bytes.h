#pragma once

#include <cstring>
#include <type_traits>
#include <vector>

namespace pantocat::packed
{
/**
 * The byte packing of the studies' MPI messages: values of trivially copyable
 * types appended to a byte buffer and read back in the same order (both ranks
 * run the same build, so no byte order or padding questions arise).
 */
template <typename T>
void put(std::vector<char>& buffer, const T& value)
{
  static_assert(std::is_trivially_copyable_v<T>);
  const char* p = reinterpret_cast<const char*>(&value);
  buffer.insert(buffer.end(), p, p + sizeof(T));
}

/// The value at @p position; advances @p position past it.
template <typename T>
T get(const std::vector<char>& buffer, std::size_t& position)
{
  static_assert(std::is_trivially_copyable_v<T>);
  T value;
  std::memcpy(&value, buffer.data() + position, sizeof(T));
  position += sizeof(T);
  return value;
}
} // namespace pantocat::packed
