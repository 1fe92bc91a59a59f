#pragma once

#include <string>

namespace pantocat
{
/**
 * Writes @p x at @p first as printf's "%.10g" does (std::to_chars with
 * chars_format::general and precision 10): ten significant digits, correctly
 * rounded from the binary value, trailing zeros removed, fixed notation for
 * decimal exponents -4 ... 9 and "d.ddde+XX" otherwise. Returns the end of the
 * text; needs at most 17 characters at @p first.
 *
 * The time series writes about 15 numbers per time point, every step of a
 * run; this is its per-row cost. The usual case (1e-17 <= |x| <
 * 1e10: times, forces, displacements) is exact integer arithmetic: the
 * significand times 5^k in 128 bits, shifted, gives the ten-digit integer and
 * the exact remainder, so the rounding is decided from the binary value as
 * printf decides it. Exact ties (rounded by printf's rounding mode), zero,
 * tiny, large and non-finite values take std::to_chars's own path. The text
 * is the same in every case (test CsvNumber.IsPrintfsTenDigitTextForEveryValue:
 * 1.5 million values against std::to_chars); under half of std::to_chars's
 * time.
 */
char* write_csv_number(char* first, double x);

/**
 * Appends @p x to @p text as write_csv_number() writes it: the text of a
 * stream with precision 10 (and no fixed or scientific flag), without the
 * stream's locale and formatting machinery (printf's, about three times the
 * time per number: contact_force.csv and the plots' data blocks).
 */
void append_csv_number(std::string& text, double x);
} // namespace pantocat
