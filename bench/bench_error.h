#pragma once

#include <exception>
#include <iostream>

/**
 * The one-line error of a benchmark program that cannot run (a parameter
 * file it cannot read, a case that the parameters refuse): its name and the
 * reason on stderr, and exit status 1 (instead of std::terminate's abort).
 * Used by the function-try-block of each benchmark's main().
 */
inline int report_bench_error(const char* program, const std::exception& e)
{
  std::cerr << program << ": error: " << e.what() << '\n';
  return 1;
}
