// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Memory.h
 * @brief Large arrays backed by huge pages where the system offers them.
 *
 * A projection visits the points in spatial order but reads and writes the per-point arrays in
 * the input's order, which for a scanner-less cloud (a generated sphere, a merged scan) is no
 * order at all: every access lands on another page. With 4 KiB pages each such access needs a
 * page-table walk, and once the page tables themselves outgrow the last-level cache (a few
 * gigabytes of arrays) every walk goes to memory. Huge pages (2 MiB) shrink the tables 512 times.
 */
#pragma once

#include <cstddef>
#include <vector>

namespace pss
{

/**
 * Asks the system to back the pages of [data, data + bytes) that have not been touched yet with
 * huge pages (Linux's transparent huge pages, which Debian enables for regions that ask). Only
 * the whole 2 MiB pages inside the range are affected; ranges under 4 MiB, other systems and a
 * refusal change nothing: this is a hint, never a requirement.
 */
void adviseHugePages(void* data, std::size_t bytes);

/// Resizes @p values to @p n; memory it has to allocate for that is advised as huge pages first.
template <class T>
void resizeOnHugePages(std::vector<T>& values, std::size_t n)
{
  if (values.capacity() < n)
  {
    std::vector<T> fresh;
    fresh.reserve(n);
    adviseHugePages(fresh.data(), n * sizeof(T));
    fresh.assign(values.begin(), values.end());
    values.swap(fresh);
  }
  values.resize(n);
}

} // namespace pss
