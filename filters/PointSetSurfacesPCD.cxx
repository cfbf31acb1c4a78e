// SPDX-License-Identifier: BSD-3-Clause
#include "PointSetSurfacesPCD.h"

#include "PointSetSurfacesPCDBody.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string_view>

namespace pss_pcd
{

using namespace detail;

namespace detail
{

[[noreturn]] void Fail(const std::string& message)
{
  throw std::runtime_error(message);
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

}

namespace
{

// More elements per point than any PCL point type has (its largest, a 308-bin histogram, is far
// below): a larger COUNT is a corrupt header, not a feature.
constexpr std::uint64_t kMaximumCount = 1u << 20;

std::string LineLabel(std::size_t line)
{
  return "header line " + std::to_string(line) + ": ";
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
    for (const char c : field.name)
    {
      // A control character (NUL above all, which would cut the array's name short) is corruption.
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      {
        Fail("field " + std::to_string(f + 1) + ": its name has a control character (byte " +
          std::to_string(static_cast<int>(static_cast<unsigned char>(c))) + ")");
      }
    }
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
  const auto tokens = pss_vtk::SplitWords(text);
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
  std::size_t headerLines = 0;
  for (std::size_t i = 0; i < bodyOffset; ++i)
  {
    headerLines += file[i] == '\n';
  }
  DecodeBody(header, body, available, headerLines, cloud.columns);
  return cloud;
}

namespace
{

// A file's bytes, mapped into memory (read into a buffer where mapping is not possible): a cloud
// of hundreds of megabytes is decoded straight from the page cache, without a copy.
class FileBytes
{
public:
  explicit FileBytes(const std::string& path)
  {
    const int fd = ::open(path.c_str(), O_RDONLY);
    if (fd < 0)
    {
      Fail("cannot open " + path);
    }
    struct stat info{};
    if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode))
    {
      ::close(fd);
      Fail("cannot read " + path + " (not a regular file)");
    }
    this->Size = static_cast<std::size_t>(info.st_size);
    if (this->Size > 0)
    {
      void* mapped = ::mmap(nullptr, this->Size, PROT_READ, MAP_PRIVATE, fd, 0);
      if (mapped != MAP_FAILED)
      {
        this->Mapped = static_cast<const unsigned char*>(mapped);
      }
      else
      {
        this->Buffer.resize(this->Size);
        const ssize_t got = ::pread(fd, this->Buffer.data(), this->Size, 0);
        if (got < 0 || static_cast<std::size_t>(got) != this->Size)
        {
          ::close(fd);
          Fail("cannot read " + path);
        }
      }
    }
    ::close(fd);
  }
  ~FileBytes()
  {
    if (this->Mapped)
    {
      ::munmap(const_cast<unsigned char*>(this->Mapped), this->Size);
    }
  }
  FileBytes(const FileBytes&) = delete;
  FileBytes& operator=(const FileBytes&) = delete;

  const unsigned char* data() const { return this->Mapped ? this->Mapped : this->Buffer.data(); }
  std::size_t size() const { return this->Size; }

private:
  const unsigned char* Mapped = nullptr;
  Bytes Buffer;
  std::size_t Size = 0;
};

}

Cloud ReadFile(const std::string& path)
{
  const FileBytes file(path);
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
  EncodeBody(cloud, out);
  return out;
}

}
