#pragma once

#include <cstdint>
#include <cstring>
#include <string>
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

/// A string: its length, then its characters.
inline void put_string(std::vector<char>& buffer, const std::string& s)
{
  put(buffer, static_cast<std::uint64_t>(s.size()));
  buffer.insert(buffer.end(), s.begin(), s.end());
}

/// The string at @p position; advances @p position past it.
inline std::string get_string(const std::vector<char>& buffer, std::size_t& position)
{
  const auto length = get<std::uint64_t>(buffer, position);
  std::string s(buffer.data() + position, length);
  position += length;
  return s;
}

/// A vector of trivially copyable values: its size, then the values.
template <typename T>
void put_vector(std::vector<char>& buffer, const std::vector<T>& v)
{
  put(buffer, static_cast<std::uint64_t>(v.size()));
  for (const T& x : v)
    put(buffer, x);
}

/// The vector at @p position; advances @p position past it.
template <typename T>
std::vector<T> get_vector(const std::vector<char>& buffer, std::size_t& position)
{
  std::vector<T> v(get<std::uint64_t>(buffer, position));
  for (T& x : v)
    x = get<T>(buffer, position);
  return v;
}
} // namespace pantocat::packed
