// SPDX-License-Identifier: BSD-3-Clause
#include "PointSetSurfacesPCD.h"

extern "C"
{
#include <lzf.h>
}

#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string_view>

namespace pss_pcd
{

namespace
{

// An LZF back reference is at most 3 bytes for 264 output bytes, so no LZF block expands more
// than 88 times: a header claiming more is refused before the output is allocated.
constexpr std::uint64_t kLzfMaximumRatio = 88;
// More elements per point than any PCL point type has (its largest, a 308-bin histogram, is far
// below): a larger COUNT is a corrupt header, not a feature.
constexpr std::uint64_t kMaximumCount = 1u << 20;

[[noreturn]] void Fail(const std::string& message)
{
  throw std::runtime_error(message);
}

std::string LineLabel(std::size_t line)
{
  return "header line " + std::to_string(line) + ": ";
}

std::vector<std::string_view> Tokens(std::string_view line)
{
  std::vector<std::string_view> out;
  std::size_t i = 0;
  while (i < line.size())
  {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r'))
    {
      ++i;
    }
    const std::size_t begin = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r')
    {
      ++i;
    }
    if (i > begin)
    {
      out.push_back(line.substr(begin, i - begin));
    }
  }
  return out;
}

// A non-negative decimal integer, the whole token; what it is called goes into the message.
std::uint64_t ParseCount(std::string_view token, const std::string& what, std::size_t line)
{
  std::uint64_t value = 0;
  const char* end = token.data() + token.size();
  const auto result = std::from_chars(token.data(), end, value);
  if (result.ec != std::errc() || result.ptr != end)
  {
    Fail(LineLabel(line) + what + " '" + std::string(token) + "' is not a non-negative integer" +
      (result.ec == std::errc::result_out_of_range ? " below 2^64" : ""));
  }
  return value;
}

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

// Overflow-checked a * b.
bool Multiply(std::uint64_t a, std::uint64_t b, std::uint64_t& out)
{
  if (a != 0 && b > std::numeric_limits<std::uint64_t>::max() / a)
  {
    return false;
  }
  out = a * b;
  return true;
}

struct HeaderLines
{
  std::vector<std::string_view> fields, sizes, types, counts;
  bool hasWidth = false, hasHeight = false, hasPoints = false;
};

void CheckFields(Header& header, const HeaderLines& lines)
{
  if (lines.fields.empty())
  {
    Fail("the header has no FIELDS line");
  }
  const std::size_t n = lines.fields.size();
  if (lines.sizes.size() != n || lines.types.size() != n || (!lines.counts.empty() && lines.counts.size() != n))
  {
    Fail("the header names " + std::to_string(n) + " fields but has " + std::to_string(lines.sizes.size()) +
      " SIZE, " + std::to_string(lines.types.size()) + " TYPE and " +
      (lines.counts.empty() ? std::string("no") : std::to_string(lines.counts.size())) + " COUNT entries");
  }

  for (std::size_t f = 0; f < n; ++f)
  {
    Field field;
    field.name = std::string(lines.fields[f]);
    const std::string label = "field '" + field.name + "': ";
    const std::string_view size = lines.sizes[f];
    if (size != "1" && size != "2" && size != "4" && size != "8")
    {
      Fail(label + "SIZE " + std::string(size) + " is not 1, 2, 4 or 8");
    }
    field.size = static_cast<std::size_t>(size[0] - '0');
    const std::string_view type = lines.types[f];
    if (type != "I" && type != "U" && type != "F")
    {
      Fail(label + "TYPE " + std::string(type) + " is not I, U or F");
    }
    field.type = type[0];
    if (field.type == 'F' && field.size < 4)
    {
      Fail(label + "TYPE F needs SIZE 4 or 8, not " + std::string(size));
    }
    std::uint64_t count = 1;
    if (!lines.counts.empty())
    {
      count = ParseCount(lines.counts[f], "COUNT", 0);
      if (count == 0 || count > kMaximumCount)
      {
        Fail(label + "COUNT " + std::to_string(count) + " is outside [1, 2^20]");
      }
    }
    field.count = static_cast<std::size_t>(count);

    for (const Field& other : header.fields)
    {
      if (other.name == field.name && field.name != "_")
      {
        Fail("the field '" + field.name + "' appears twice");
      }
    }
    header.fields.push_back(field);
  }

}

void CheckDimensions(Header& header, const HeaderLines& lines)
{
  if (!lines.hasWidth && !lines.hasPoints)
  {
    Fail("the header has neither WIDTH nor POINTS");
  }
  if (!lines.hasWidth)
  {
    header.width = header.points;
    header.height = 1;
  }
  std::uint64_t grid = 0;
  if (!Multiply(header.width, header.height, grid))
  {
    Fail("WIDTH " + std::to_string(header.width) + " x HEIGHT " + std::to_string(header.height) + " overflows");
  }
  if (!lines.hasPoints)
  {
    header.points = grid;
  }
  if (header.points != grid)
  {
    Fail("POINTS " + std::to_string(header.points) + " is not WIDTH x HEIGHT (" + std::to_string(header.width) +
      " x " + std::to_string(header.height) + ")");
  }
  if (header.height == 0 && header.width != 0)
  {
    Fail("HEIGHT 0 with WIDTH " + std::to_string(header.width));
  }
}

DataKind ParseDataKind(std::string_view token, std::size_t line)
{
  if (token == "ascii")
    return DataKind::Ascii;
  if (token == "binary")
    return DataKind::Binary;
  if (token == "binary_compressed")
    return DataKind::BinaryCompressed;
  Fail(LineLabel(line) + "unknown DATA kind '" + std::string(token) + "' (ascii, binary or binary_compressed)");
}

// One header line into @p header / @p lines; returns true on the DATA line.
bool ParseLine(std::string_view text, std::size_t line, Header& header, HeaderLines& lines, std::string& seen)
{
  const auto tokens = Tokens(text);
  if (tokens.empty() || tokens[0].front() == '#')
  {
    return false;
  }
  const std::string keyword(tokens[0]);
  if (seen.find(" " + keyword + " ") != std::string::npos)
  {
    Fail(LineLabel(line) + keyword + " appears twice");
  }
  seen += " " + keyword + " ";
  const std::vector<std::string_view> values(tokens.begin() + 1, tokens.end());
  const auto one = [&]() {
    if (values.size() != 1)
    {
      Fail(LineLabel(line) + keyword + " takes one value, not " + std::to_string(values.size()));
    }
    return values[0];
  };
  if (keyword == "VERSION")
    header.version = std::string(one());
  else if (keyword == "FIELDS" || keyword == "COLUMNS")
    lines.fields = values;
  else if (keyword == "SIZE")
    lines.sizes = values;
  else if (keyword == "TYPE")
    lines.types = values;
  else if (keyword == "COUNT")
    lines.counts = values;
  else if (keyword == "WIDTH")
  {
    header.width = ParseCount(one(), "WIDTH", line);
    lines.hasWidth = true;
  }
  else if (keyword == "HEIGHT")
  {
    header.height = ParseCount(one(), "HEIGHT", line);
    lines.hasHeight = true;
  }
  else if (keyword == "POINTS")
  {
    header.points = ParseCount(one(), "POINTS", line);
    lines.hasPoints = true;
  }
  else if (keyword == "VIEWPOINT")
  {
    if (values.size() != 7)
    {
      Fail(LineLabel(line) + "VIEWPOINT takes 7 numbers (tx ty tz qw qx qy qz), not " + std::to_string(values.size()));
    }
    for (std::size_t k = 0; k < 7; ++k)
    {
      if (!ParseNumber(values[k], header.viewpoint[k]) || !std::isfinite(header.viewpoint[k]))
      {
        Fail(LineLabel(line) + "VIEWPOINT value '" + std::string(values[k]) + "' is not a finite number");
      }
    }
    header.hasViewpoint = true;
  }
  else if (keyword == "DATA")
  {
    header.data = ParseDataKind(one(), line);
    return true;
  }
  else
  {
    Fail(LineLabel(line) + "unknown keyword '" + keyword + "'");
  }
  return false;
}

// Offsets of each field's column in the field-major body.
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
  const unsigned int produced = lzf_decompress(body + 8, static_cast<unsigned int>(compressed), columns.bytes.data(),
    static_cast<unsigned int>(uncompressed));
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
    const auto tokens = Tokens(text.substr(position, end - position));
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

template <typename T>
void AppendNumber(std::string& out, T value)
{
  char buffer[64];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  out.append(buffer, result.ptr);
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

void CheckColumns(const Cloud& cloud)
{
  const Header& header = cloud.header;
  if (cloud.columns.start != ColumnStarts(header) ||
    cloud.columns.bytes.size() != static_cast<std::size_t>(header.points) * header.pointSize())
  {
    Fail("the columns do not match the header's fields and POINTS");
  }
}

} // namespace

std::size_t Header::pointSize() const
{
  std::size_t size = 0;
  for (const Field& field : this->fields)
  {
    size += field.bytesPerPoint();
  }
  return size;
}

const char* DataKindName(DataKind kind)
{
  switch (kind)
  {
    case DataKind::Ascii: return "ascii";
    case DataKind::Binary: return "binary";
    default: return "binary_compressed";
  }
}

Header ParseHeader(const unsigned char* file, std::size_t size, std::size_t& bodyOffset)
{
  if (size == 0)
  {
    Fail("the file is empty");
  }
  const std::string_view text(reinterpret_cast<const char*>(file), size);
  Header header;
  HeaderLines lines;
  std::string seen;
  std::size_t position = 0, line = 0;
  bool data = false;
  while (!data)
  {
    if (position >= text.size())
    {
      Fail("the header ends without a DATA line (a header only, or not a PCD file)");
    }
    std::size_t end = text.find('\n', position);
    if (end == std::string_view::npos)
    {
      end = text.size();
    }
    ++line;
    data = ParseLine(text.substr(position, end - position), line, header, lines, seen);
    position = std::min(end + 1, text.size());
  }
  bodyOffset = position;
  CheckFields(header, lines);
  CheckDimensions(header, lines);
  return header;
}

Cloud Decode(const unsigned char* file, std::size_t size)
{
  Cloud cloud;
  std::size_t bodyOffset = 0;
  cloud.header = ParseHeader(file, size, bodyOffset);
  const Header& header = cloud.header;
  const unsigned char* body = file + bodyOffset;
  const std::size_t available = size - bodyOffset;
  if (header.points == 0)
  {
    cloud.columns.start = ColumnStarts(header);
    return cloud;
  }
  switch (header.data)
  {
    case DataKind::Binary: DecodeBinary(header, body, available, cloud.columns); break;
    case DataKind::BinaryCompressed: DecodeCompressed(header, body, available, cloud.columns); break;
    case DataKind::Ascii:
    {
      std::size_t headerLines = 0;
      for (std::size_t i = 0; i < bodyOffset; ++i)
      {
        headerLines += file[i] == '\n';
      }
      DecodeAscii(header, body, available, headerLines, cloud.columns);
      break;
    }
  }
  return cloud;
}

Cloud ReadFile(const std::string& path)
{
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in)
  {
    Fail("cannot open " + path);
  }
  const std::streamoff size = in.tellg();
  if (size < 0)
  {
    Fail("cannot read " + path);
  }
  std::vector<unsigned char> file(static_cast<std::size_t>(size));
  in.seekg(0);
  if (size > 0 && !in.read(reinterpret_cast<char*>(file.data()), size))
  {
    Fail("cannot read " + path);
  }
  try
  {
    return Decode(file.data(), file.size());
  }
  catch (const std::runtime_error& error)
  {
    Fail(path + ": " + error.what());
  }
}

std::string FormatHeader(const Header& header)
{
  std::string out = "# .PCD v0.7 - Point Cloud Data file format\nVERSION 0.7\n";
  const auto list = [&out, &header](const char* keyword, auto item) {
    out += keyword;
    for (const Field& field : header.fields)
    {
      out += ' ';
      out += item(field);
    }
    out += '\n';
  };
  list("FIELDS", [](const Field& f) { return f.name; });
  list("SIZE", [](const Field& f) { return std::to_string(f.size); });
  list("TYPE", [](const Field& f) { return std::string(1, f.type); });
  list("COUNT", [](const Field& f) { return std::to_string(f.count); });
  out += "WIDTH " + std::to_string(header.width) + "\nHEIGHT " + std::to_string(header.height) + "\nVIEWPOINT";
  for (double v : header.viewpoint)
  {
    out += ' ';
    AppendNumber(out, v);
  }
  out += "\nPOINTS " + std::to_string(header.points) + "\nDATA " + DataKindName(header.data) + "\n";
  return out;
}

std::vector<unsigned char> Encode(const Cloud& cloud)
{
  CheckColumns(cloud);
  const Header& header = cloud.header;
  const std::string head = FormatHeader(header);
  std::vector<unsigned char> out(head.begin(), head.end());
  const std::size_t n = static_cast<std::size_t>(header.points);
  const std::vector<unsigned char>& bytes = cloud.columns.bytes;
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
    return out;
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
    return out;
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
  return out;
}

}
