// SPDX-License-Identifier: BSD-3-Clause
#include "pss/Memory.h"

#include <cstdint>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace pss
{

void adviseHugePages(void* data, std::size_t bytes)
{
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  constexpr std::uintptr_t Huge = std::uintptr_t(1) << 21;
  if (data == nullptr || bytes < 2 * Huge)
  {
    return;
  }
  const auto begin = reinterpret_cast<std::uintptr_t>(data);
  const std::uintptr_t first = (begin + Huge - 1) & ~(Huge - 1);
  const std::uintptr_t last = (begin + bytes) & ~(Huge - 1);
  if (last > first)
  {
    // A refusal (no transparent huge pages, a kernel without them) leaves ordinary pages.
    (void)::madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
  }
#else
  (void)data;
  (void)bytes;
#endif
}

} // namespace pss
