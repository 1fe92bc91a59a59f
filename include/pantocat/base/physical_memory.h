#pragma once

#include <unistd.h>

namespace pantocat
{
/// The physical memory of this machine [bytes] (sysconf); 0 if unknown.
inline double physical_memory_bytes()
{
  const long pages = sysconf(_SC_PHYS_PAGES), page_size = sysconf(_SC_PAGE_SIZE);
  if (pages <= 0 || page_size <= 0)
    return 0.;
  return static_cast<double>(pages) * static_cast<double>(page_size);
}
} // namespace pantocat
