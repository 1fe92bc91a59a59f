#include <pantocat/io/csv_number.h>

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>

namespace pantocat
{
namespace
{
/// The exact reference: std::to_chars's "%.10g" (17 characters suffice).
char* exact_g10(char* first, const double x)
{
  return std::to_chars(first, first + 24, x, std::chars_format::general, 10).ptr;
}

/// A 128-bit unsigned integer (a GCC and Clang extension on 64-bit targets).
__extension__ typedef unsigned __int128 Uint128;

/// 5^k for k = 0 ... 27 (5^27 < 2^63).
constexpr std::array<std::uint64_t, 28> powers_of_five = []
{
  std::array<std::uint64_t, 28> p{};
  std::uint64_t v = 1;
  for (auto& e : p)
  {
    e = v;
    v *= 5;
  }
  return p;
}();

/// How y = |x| 10^k rounds to an integer n: exactly, from the binary value.
enum class Rounding
{
  down,
  up,
  tie
};

/**
 * y = m 2^s 10^k (m the 53-bit significand of |x|, s its binary exponent,
 * 0 <= k <= 27) as the exact integer P = m 5^k (128 bits) shifted by s + k:
 * its integer part @p n and how it rounds.
 */
Rounding scaled_integer(const std::uint64_t m, const int s, const int k, std::uint64_t& n)
{
  const Uint128 P = static_cast<Uint128>(m) * powers_of_five[k];
  const int shift = -(s + k);
  if (shift <= 0) // y is an integer (here below 2^64: y < 10^11)
  {
    n = static_cast<std::uint64_t>(P << -shift);
    return Rounding::down;
  }
  n = static_cast<std::uint64_t>(P >> shift);
  const Uint128 remainder = P - (static_cast<Uint128>(n) << shift);
  const Uint128 half = static_cast<Uint128>(1) << (shift - 1);
  return remainder < half ? Rounding::down
                          : (remainder > half ? Rounding::up : Rounding::tie);
}

/// "00", "01", ..., "99": two digits a lookup.
constexpr std::array<char, 200> digit_pairs = []
{
  std::array<char, 200> d{};
  for (int i = 0; i < 100; ++i)
  {
    d[2 * i] = static_cast<char>('0' + i / 10);
    d[2 * i + 1] = static_cast<char>('0' + i % 10);
  }
  return d;
}();

/// The five digits of @p x < 10^5 at @p d: one digit, then two pairs.
void five_digits(char* d, std::uint32_t x)
{
  d[0] = static_cast<char>('0' + x / 10000);
  x %= 10000;
  std::memcpy(d + 1, &digit_pairs[2 * (x / 100)], 2);
  std::memcpy(d + 3, &digit_pairs[2 * (x % 100)], 2);
}

/// The text of ten significant digits @p n (10^9 <= n < 10^10) with decimal
/// exponent @p e, trailing zeros removed, in %g's layout for precision 10.
char* layout_g10(char* p, const std::uint64_t n, const int e)
{
  // The two halves are independent chains of multiplications (division by a
  // constant), not ten in a row.
  char digits[10];
  five_digits(digits, static_cast<std::uint32_t>(n / 100000));
  five_digits(digits + 5, static_cast<std::uint32_t>(n % 100000));
  int length = 10;
  while (length > 1 && digits[length - 1] == '0')
    --length;
  if (e >= -4 && e < 10) // fixed notation
  {
    if (e < 0)
    {
      *p++ = '0';
      *p++ = '.';
      for (int i = -1; i > e; --i)
        *p++ = '0';
      for (int i = 0; i < length; ++i)
        *p++ = digits[i];
      return p;
    }
    for (int i = 0; i <= e; ++i)
      *p++ = digits[i];
    if (length > e + 1)
    {
      *p++ = '.';
      for (int i = e + 1; i < length; ++i)
        *p++ = digits[i];
    }
    return p;
  }
  *p++ = digits[0]; // scientific notation, |e| < 100 here
  if (length > 1)
  {
    *p++ = '.';
    for (int i = 1; i < length; ++i)
      *p++ = digits[i];
  }
  *p++ = 'e';
  *p++ = e < 0 ? '-' : '+';
  const int m = std::abs(e);
  *p++ = static_cast<char>('0' + m / 10);
  *p++ = static_cast<char>('0' + m % 10);
  return p;
}
} // namespace

char* write_csv_number(char* first, const double x)
{
  const double a = std::abs(x);
  if (!(a >= 1e-17 && a < 1e10)) // zero, tiny, large, not finite
    return exact_g10(first, x);
  std::uint64_t bits;
  std::memcpy(&bits, &a, sizeof bits);
  const int e2 = static_cast<int>(bits >> 52) - 1023; // a is normal and positive here
  const std::uint64_t m =
      (bits & ((std::uint64_t(1) << 52) - 1)) | (std::uint64_t(1) << 52);
  const int s = e2 - 52;
  // The decimal exponent e, 10^e <= a < 10^(e+1): floor(e2 log10 2) in integer
  // arithmetic (78913 / 2^18 = 0.30103) is e or e - 1.
  int e = (e2 * 78913) >> 18;
  std::uint64_t n;
  Rounding r = scaled_integer(m, s, 9 - e, n);
  if (n >= 10000000000ULL)
  {
    if (9 - (e + 1) < 0)
      return exact_g10(first, x);
    r = scaled_integer(m, s, 9 - ++e, n);
  }
  if (r == Rounding::tie) // exactly half way: printf's rounding mode decides
    return exact_g10(first, x);
  if (r == Rounding::up && ++n == 10000000000ULL)
  {
    n = 1000000000ULL; // 9.999999999|5... rounds up to the next decade
    ++e;
  }
  char* p = first;
  if (std::signbit(x))
    *p++ = '-';
  return layout_g10(p, n, e);
}

void append_csv_number(std::string& text, const double x)
{
  char digits[24];
  text.append(digits, write_csv_number(digits, x));
}
} // namespace pantocat
