// SPDX-License-Identifier: BSD-3-Clause
// The bodies of PCD files: binary (point-major), binary_compressed (one LZF block, field-major) and
// ascii, decoded into columns and encoded from them. The header is PointSetSurfacesPCD.cxx's.
#include "PointSetSurfacesPCDBody.h"

extern "C"
{
#include <lzf.h>
}

#include <sys/mman.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <thread>

namespace pss_pcd
{
namespace detail
{

namespace
{

// An LZF back reference is at most 3 bytes for 264 output bytes, so no LZF block expands more
// than 88 times: a header claiming more is refused before the output is allocated.
constexpr std::uint64_t kLzfMaximumRatio = 88;

} // namespace

std::size_t DecodeLzf(const unsigned char* in, std::size_t inSize, unsigned char* out, std::size_t outSize)
{
  // liblzf's own decoder copies byte by byte. PCD's float columns hardly compress, so the block is
  // mostly literal runs of 32 bytes: copying those (and back references at least 8 bytes behind)
  // in whole words, while there is room to copy past the run's end, decodes 2.5x faster. The
  // checks are liblzf's, in its order, so both return the same on every input (tested, fuzzed).
  const unsigned char* ip = in;
  const unsigned char* const inEnd = in + inSize;
  std::size_t at = 0;
  while (ip < inEnd)
  {
    const unsigned int control = *ip++;
    if (control < 32)
    {
      const std::size_t length = control + 1;
      if (length > outSize - at || length > static_cast<std::size_t>(inEnd - ip))
      {
        return 0;
      }
      std::memcpy(out + at, ip, outSize - at >= 32 && inEnd - ip >= 32 ? 32 : length); // length <= 32
      at += length;
      ip += length;
      continue;
    }
    std::size_t length = control >> 5;
    if (ip >= inEnd)
    {
      return 0;
    }
    if (length == 7)
    {
      length += *ip++;
      if (ip >= inEnd)
      {
        return 0;
      }
    }
    const std::size_t back = (static_cast<std::size_t>(control & 0x1f) << 8) + *ip++ + 1;
    length += 2;
    if (length > outSize - at || back > at)
    {
      return 0;
    }
    unsigned char* to = out + at;
    const unsigned char* from = to - back;
    if (back >= 8 && outSize - at >= length + 8)
    {
      for (std::size_t k = 0; k < length; k += 8)
      {
        std::memcpy(to + k, from + k, 8); // reads only bytes already written: back >= 8
      }
    }
    else
    {
      for (std::size_t k = 0; k < length; ++k)
      {
        to[k] = from[k];
      }
    }
    at += length;
  }
  return at;
}

namespace
{

void DecodeBinary(const Header& header, const unsigned char* body, std::size_t available, Columns& columns)
{
  const std::size_t record = header.pointSize();
  if (header.points > available / record)
  {
    Fail("truncated: POINTS " + std::to_string(header.points) + " x " + std::to_string(record) +
      " bytes need more than the " + std::to_string(available) + " bytes after the header");
  }
  const std::size_t n = static_cast<std::size_t>(header.points);
  columns.start = ColumnStarts(header);
  columns.bytes.resize(n * record);
  std::size_t fieldOffset = 0;
  for (std::size_t f = 0; f < header.fields.size(); ++f)
  {
    const std::size_t width = header.fields[f].bytesPerPoint();
    unsigned char* out = columns.bytes.data() + columns.start[f];
    const unsigned char* in = body + fieldOffset;
    for (std::size_t i = 0; i < n; ++i)
    {
      std::memcpy(out + i * width, in + i * record, width);
    }
    fieldOffset += width;
  }
}

std::uint32_t LoadUInt32(const unsigned char* p)
{
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
    static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

void StoreUInt32(std::uint32_t value, unsigned char* p)
{
  for (int b = 0; b < 4; ++b)
  {
    p[b] = static_cast<unsigned char>(value >> (8 * b));
  }
}

// Runs @p fill, which writes @p bytes from the front, while a second thread asks the kernel to map
// the pages ahead of it (MADV_POPULATE_WRITE, which leaves their contents alone): a fresh page's
// first touch, the kernel zeroing it, costs about as much as LZF's decoding, and the two then
// overlap. Only for bodies of 64 MiB and more, and where the kernel has it (Linux 5.14).
template <typename Fill>
void WhileFaultingIn(Bytes& bytes, Fill&& fill)
{
#ifdef MADV_POPULATE_WRITE
  constexpr std::size_t page = 4096;
  if (bytes.size() >= (std::size_t(64) << 20) && std::thread::hardware_concurrency() >= 2)
  {
    const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(bytes.data()) + page - 1) & ~(page - 1);
    const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(bytes.data()) + bytes.size()) & ~(page - 1);
    std::thread populate([begin, end]() {
      const std::uintptr_t chunk = std::uintptr_t(4) << 20;
      for (std::uintptr_t at = begin; at < end; at += chunk)
      {
        if (::madvise(reinterpret_cast<void*>(at), std::min(chunk, end - at), MADV_POPULATE_WRITE) != 0)
        {
          return; // an older kernel: the decoder faults the pages in itself
        }
      }
    });
    fill();
    populate.join();
    return;
  }
#endif
  fill();
}

void DecodeCompressed(const Header& header, const unsigned char* body, std::size_t available, Columns& columns)
{
  if (available < 8)
  {
    if (header.points == 0 && available == 0)
    {
      return;
    }
    Fail("truncated: binary_compressed needs 8 bytes of sizes after the header, the file has " +
      std::to_string(available));
  }
  const std::uint64_t compressed = LoadUInt32(body);
  const std::uint64_t uncompressed = LoadUInt32(body + 4);
  std::uint64_t expected = 0;
  if (!Multiply(header.points, header.pointSize(), expected) || uncompressed != expected)
  {
    Fail("the compressed block says it holds " + std::to_string(uncompressed) + " bytes, but POINTS " +
      std::to_string(header.points) + " x " + std::to_string(header.pointSize()) + " bytes per point is " +
      (expected == 0 && header.points != 0 ? std::string("beyond 2^64") : std::to_string(expected)));
  }
  if (compressed > available - 8)
  {
    Fail("truncated: the compressed block's size is " + std::to_string(compressed) + " bytes, the file holds " +
      std::to_string(available - 8) + " after the header");
  }
  if (uncompressed > compressed * kLzfMaximumRatio)
  {
    Fail("the compressed block claims " + std::to_string(uncompressed) + " bytes from " + std::to_string(compressed) +
      ": more than LZF's largest ratio (88:1) can give");
  }
  columns.start = ColumnStarts(header);
  if (uncompressed == 0)
  {
    return;
  }
  columns.bytes.resize(static_cast<std::size_t>(uncompressed));
  std::size_t produced = 0;
  WhileFaultingIn(columns.bytes, [&]() {
    produced = DecodeLzf(body + 8, static_cast<std::size_t>(compressed), columns.bytes.data(), columns.bytes.size());
  });
  if (produced != uncompressed)
  {
    Fail("the LZF block is corrupt: it decompresses to " +
      (produced == 0 ? std::string("nothing valid") : std::to_string(produced) + " bytes") + ", the header says " +
      std::to_string(uncompressed));
  }
}

// One ASCII value into @p out (the field's element size), range-checked.
bool ParseElement(std::string_view token, const Field& field, unsigned char* out)
{
  const auto store = [&](auto value) {
    std::memcpy(out, &value, sizeof value);
    return true;
  };
  if (field.type == 'F')
  {
    if (field.size == 4)
    {
      float value = 0;
      return ParseNumber(token, value) && store(value);
    }
    double value = 0;
    return ParseNumber(token, value) && store(value);
  }
  if (field.type == 'U')
  {
    std::uint64_t value = 0;
    if (!ParseNumber(token, value) || (field.size < 8 && value >> (8 * field.size) != 0))
    {
      return false;
    }
    switch (field.size)
    {
      case 1: return store(static_cast<std::uint8_t>(value));
      case 2: return store(static_cast<std::uint16_t>(value));
      case 4: return store(static_cast<std::uint32_t>(value));
      default: return store(value);
    }
  }
  std::int64_t value = 0;
  if (!ParseNumber(token, value))
  {
    return false;
  }
  const std::int64_t limit = field.size < 8 ? std::int64_t(1) << (8 * field.size - 1) : 0;
  if (field.size < 8 && (value < -limit || value >= limit))
  {
    return false;
  }
  switch (field.size)
  {
    case 1: return store(static_cast<std::int8_t>(value));
    case 2: return store(static_cast<std::int16_t>(value));
    case 4: return store(static_cast<std::int32_t>(value));
    default: return store(value);
  }
}

void DecodeAscii(const Header& header, const unsigned char* body, std::size_t available, std::size_t firstLine,
  Columns& columns)
{
  std::size_t values = 0;
  for (const Field& field : header.fields)
  {
    values += field.count;
  }
  // Every value takes a character and a separator: a count beyond that is refused before allocating.
  if (header.points > (available / 2 + 1) / values)
  {
    Fail("truncated: POINTS " + std::to_string(header.points) + " x " + std::to_string(values) +
      " ASCII values cannot fit in the " + std::to_string(available) + " bytes after the header");
  }
  const std::size_t n = static_cast<std::size_t>(header.points);
  columns.start = ColumnStarts(header);
  columns.bytes.resize(n * header.pointSize());
  const std::string_view text(reinterpret_cast<const char*>(body), available);
  std::size_t position = 0, line = firstLine;
  std::size_t point = 0;
  while (point < n && position < text.size())
  {
    std::size_t end = text.find('\n', position);
    if (end == std::string_view::npos)
    {
      end = text.size();
    }
    const auto tokens = pss_vtk::SplitWords(text.substr(position, end - position));
    position = end + 1;
    ++line;
    if (tokens.empty())
    {
      continue;
    }
    if (tokens.size() != values)
    {
      Fail("line " + std::to_string(line) + ": expected " + std::to_string(values) + " values, found " +
        std::to_string(tokens.size()));
    }
    std::size_t t = 0;
    for (std::size_t f = 0; f < header.fields.size(); ++f)
    {
      const Field& field = header.fields[f];
      for (std::size_t c = 0; c < field.count; ++c, ++t)
      {
        unsigned char* out = columns.bytes.data() + columns.start[f] + (point * field.count + c) * field.size;
        if (!ParseElement(tokens[t], field, out))
        {
          Fail("line " + std::to_string(line) + ": '" + std::string(tokens[t]) + "' is not a value of field '" +
            field.name + "' (TYPE " + field.type + ", SIZE " + std::to_string(field.size) + ")");
        }
      }
    }
    ++point;
  }
  if (point < n)
  {
    Fail("truncated: the body has " + std::to_string(point) + " points, POINTS says " + std::to_string(n));
  }
}

void AppendElement(std::string& out, const Field& field, const unsigned char* p)
{
  const auto load = [p](auto value) {
    std::memcpy(&value, p, sizeof value);
    return value;
  };
  if (field.type == 'F')
  {
    field.size == 4 ? AppendNumber(out, load(float())) : AppendNumber(out, load(double()));
    return;
  }
  switch (static_cast<int>(field.size) * (field.type == 'U' ? 1 : -1))
  {
    case 1: AppendNumber(out, load(std::uint8_t())); break;
    case 2: AppendNumber(out, load(std::uint16_t())); break;
    case 4: AppendNumber(out, load(std::uint32_t())); break;
    case 8: AppendNumber(out, load(std::uint64_t())); break;
    case -1: AppendNumber(out, load(std::int8_t())); break;
    case -2: AppendNumber(out, load(std::int16_t())); break;
    case -4: AppendNumber(out, load(std::int32_t())); break;
    default: AppendNumber(out, load(std::int64_t())); break;
  }
}

} // namespace

void CheckColumns(const Cloud& cloud)
{
  const Header& header = cloud.header;
  if (cloud.columns.start != ColumnStarts(header) ||
    cloud.columns.bytes.size() != static_cast<std::size_t>(header.points) * header.pointSize())
  {
    Fail("the columns do not match the header's fields and POINTS");
  }
}

void DecodeBody(const Header& header, const unsigned char* body, std::size_t available, std::size_t headerLines,
  Columns& columns)
{
  switch (header.data)
  {
    case DataKind::Binary: DecodeBinary(header, body, available, columns); break;
    case DataKind::BinaryCompressed: DecodeCompressed(header, body, available, columns); break;
    case DataKind::Ascii: DecodeAscii(header, body, available, headerLines, columns); break;
  }
}

void EncodeBody(const Cloud& cloud, std::vector<unsigned char>& out)
{
  const Header& header = cloud.header;
  const std::size_t n = static_cast<std::size_t>(header.points);
  const Bytes& bytes = cloud.columns.bytes;
  if (header.data == DataKind::BinaryCompressed)
  {
    const std::size_t raw = bytes.size();
    if (raw > std::numeric_limits<std::uint32_t>::max())
    {
      Fail("binary_compressed holds at most 4 GiB of point data (the block sizes are 32-bit); write binary");
    }
    const std::size_t headerSize = out.size();
    // LZF expands incompressible data by at most one byte in 32, plus a little.
    out.resize(headerSize + 8 + raw + raw / 16 + 64);
    unsigned int compressed = 0;
    if (raw > 0)
    {
      compressed = lzf_compress(bytes.data(), static_cast<unsigned int>(raw), out.data() + headerSize + 8,
        static_cast<unsigned int>(out.size() - headerSize - 8));
      if (compressed == 0)
      {
        Fail("LZF could not compress the point data");
      }
    }
    StoreUInt32(compressed, out.data() + headerSize);
    StoreUInt32(static_cast<std::uint32_t>(raw), out.data() + headerSize + 4);
    out.resize(headerSize + 8 + compressed);
    return;
  }
  if (header.data == DataKind::Binary)
  {
    const std::size_t record = header.pointSize();
    const std::size_t headerSize = out.size();
    out.resize(headerSize + n * record);
    std::size_t fieldOffset = 0;
    for (std::size_t f = 0; f < header.fields.size(); ++f)
    {
      const std::size_t width = header.fields[f].bytesPerPoint();
      const unsigned char* in = bytes.data() + cloud.columns.start[f];
      unsigned char* dst = out.data() + headerSize + fieldOffset;
      for (std::size_t i = 0; i < n; ++i)
      {
        std::memcpy(dst + i * record, in + i * width, width);
      }
      fieldOffset += width;
    }
    return;
  }
  std::string text;
  for (std::size_t i = 0; i < n; ++i)
  {
    for (std::size_t f = 0; f < header.fields.size(); ++f)
    {
      const Field& field = header.fields[f];
      for (std::size_t c = 0; c < field.count; ++c)
      {
        if (f + c > 0)
        {
          text += ' ';
        }
        AppendElement(text, field, bytes.data() + cloud.columns.start[f] + (i * field.count + c) * field.size);
      }
    }
    text += '\n';
  }
  out.insert(out.end(), text.begin(), text.end());
}

}

std::vector<std::size_t> ColumnStarts(const Header& header)
{
  std::vector<std::size_t> start;
  std::size_t offset = 0;
  for (const Field& field : header.fields)
  {
    start.push_back(offset);
    offset += static_cast<std::size_t>(header.points) * field.bytesPerPoint();
  }
  return start;
}

}

