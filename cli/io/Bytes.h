// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file Bytes.h
 * @brief Integers stored in a file's byte order, for the binary checks of PLY and VTK XML files.
 */
#ifndef pss_cli_io_Bytes_h
#define pss_cli_io_Bytes_h

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace pss_cli
{
namespace io
{

/// The unsigned integer of @p size bytes (1 to 8) at @p p, most significant byte first when
/// @p bigEndian: the same on any host.
inline std::uint64_t LoadUnsigned(const unsigned char* p, std::size_t size, bool bigEndian)
{
  std::uint64_t bits = 0;
  for (std::size_t b = 0; b < size; ++b)
  {
    bits |= static_cast<std::uint64_t>(p[bigEndian ? size - 1 - b : b]) << (8 * b);
  }
  return bits;
}

/// The two's-complement integer of @p size bytes (1 to 8) at @p p, in the given byte order.
inline std::int64_t LoadSigned(const unsigned char* p, std::size_t size, bool bigEndian)
{
  const std::uint64_t bits = LoadUnsigned(p, size, bigEndian);
  if (size < 8 && (bits >> (8 * size - 1)) != 0)
  {
    return static_cast<std::int64_t>(bits) - (std::int64_t(1) << (8 * size));
  }
  std::int64_t value = 0;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

}
}

#endif
