// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PointSetSurfacesPCDBody.h
 * @brief Private to the PCD code: the bodies' decoders and encoders (PointSetSurfacesPCDBody.cxx)
 *        and the text helpers the header parser shares with the ascii decoder.
 */
#ifndef PointSetSurfacesPCDBody_h
#define PointSetSurfacesPCDBody_h

#include "PointSetSurfacesPCD.h"
#include "PointSetSurfacesWords.h"

#include <charconv>
#include <string_view>

namespace pss_pcd
{
namespace detail
{

/// Throws std::runtime_error(@p message).
[[noreturn]] void Fail(const std::string& message);

/// Overflow-checked a * b into @p out; false when it overflows.
bool Multiply(std::uint64_t a, std::uint64_t b, std::uint64_t& out);

// A decimal number (from_chars: locale-independent, accepts nan and inf); a leading '+' allowed.
template <typename T>
bool ParseNumber(std::string_view token, T& value)
{
  if (!token.empty() && token.front() == '+')
  {
    token.remove_prefix(1);
  }
  const char* end = token.data() + token.size();
  const auto result = std::from_chars(token.data(), end, value);
  return result.ec == std::errc() && result.ptr == end;
}

/// Appends the shortest text of @p value that reads back to the same bits.
template <typename T>
void AppendNumber(std::string& out, T value)
{
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
}

/// Decodes the LZF block @p in (@p inSize bytes) into @p out (room for @p outSize bytes); returns
/// the bytes written, or 0 when the block is corrupt or would not fit: what liblzf's
/// lzf_decompress returns on the same input, faster on PCD's columns.
std::size_t DecodeLzf(const unsigned char* in, std::size_t inSize, unsigned char* out, std::size_t outSize);

/// Decodes the body after the header (@p available bytes at @p body; @p headerLines counts the
/// header's lines, for the ascii decoder's messages) into @p columns; throws on a lie or a cut.
void DecodeBody(const Header& header, const unsigned char* body, std::size_t available, std::size_t headerLines,
  Columns& columns);

/// Throws when @p cloud's columns do not match its header.
void CheckColumns(const Cloud& cloud);

/// Appends @p cloud's body, in its header's DATA kind, to @p out.
void EncodeBody(const Cloud& cloud, std::vector<unsigned char>& out);

}
}

#endif
