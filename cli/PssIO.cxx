// SPDX-License-Identifier: BSD-3-Clause
#include "PssIO.h"

#include "vtkAppendFilter.h"
#include "vtkCellArray.h"
#include "vtkCellType.h"
#include "vtkCellTypes.h"
#include "vtkDataArray.h"
#include "vtkDataCompressor.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkLZ4DataCompressor.h"
#include "vtkLZMADataCompressor.h"
#include "vtkNew.h"
#include "vtkOBJWriter.h"
#include "vtkPLYReader.h"
#include "vtkPLYWriter.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSTLWriter.h"
#include "vtkUnstructuredGrid.h"
#include "vtkWriter.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"
#include "vtkXMLUnstructuredGridReader.h"
#include "vtkXMLUnstructuredGridWriter.h"
#include "vtkZLibDataCompressor.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace pss_cli
{

namespace
{

std::string Lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string Trim(const std::string& s)
{
  const auto b = s.find_first_not_of(" \t\r\n");
  const auto e = s.find_last_not_of(" \t\r\n");
  return b == std::string::npos ? std::string() : s.substr(b, e - b + 1);
}

bool ParseDouble(const std::string& token, double& value)
{
  const std::string t = Trim(token);
  if (t.empty())
  {
    return false;
  }
  char* end = nullptr;
  errno = 0;
  value = std::strtod(t.c_str(), &end);
  return end == t.c_str() + t.size();
}

std::vector<std::string> Split(const std::string& line, bool commas)
{
  std::vector<std::string> out;
  if (commas)
  {
    std::stringstream ss(line);
    std::string item;
    while (std::getline(ss, item, ','))
    {
      out.push_back(Trim(item));
    }
  }
  else
  {
    std::istringstream ss(line);
    std::string item;
    while (ss >> item)
    {
      out.push_back(item);
    }
  }
  return out;
}

// Points (and, for CSV with a header, extra numeric columns as arrays) from a text table.
vtkSmartPointer<vtkDataSet> ReadTable(const std::string& path, bool csv)
{
  std::ifstream in(path);
  if (!in)
  {
    throw std::runtime_error("cannot open " + path);
  }
  std::vector<std::string> names;
  std::vector<std::vector<double>> columns;
  std::string line;
  std::size_t lineNumber = 0;
  std::size_t width = 0;
  while (std::getline(in, line))
  {
    ++lineNumber;
    const std::string t = Trim(line);
    if (t.empty() || t[0] == '#')
    {
      continue;
    }
    const std::vector<std::string> tokens = Split(t, csv);
    std::vector<double> values(tokens.size());
    bool numeric = true;
    for (std::size_t i = 0; i < tokens.size() && numeric; ++i)
    {
      numeric = ParseDouble(tokens[i], values[i]);
    }
    if (!numeric)
    {
      if (csv && names.empty() && columns.empty())
      {
        for (const std::string& tok : tokens)
        {
          names.push_back(Lower(tok));
        }
        continue;
      }
      throw std::runtime_error(path + ":" + std::to_string(lineNumber) + ": not a row of numbers: " + t);
    }
    if (width == 0)
    {
      width = values.size();
      if (width < 2)
      {
        throw std::runtime_error(path + ":" + std::to_string(lineNumber) + ": need at least two columns (x y)");
      }
      // Every column of the header must have its numbers (a header wider than the rows once
      // sent the x or y lookup past the last column).
      if (!names.empty() && names.size() != width)
      {
        throw std::runtime_error(path + ":" + std::to_string(lineNumber) + ": the header names " +
          std::to_string(names.size()) + " columns, this row has " + std::to_string(width));
      }
      columns.resize(width);
    }
    if (values.size() != width)
    {
      throw std::runtime_error(path + ":" + std::to_string(lineNumber) + ": expected " + std::to_string(width) +
        " columns, found " + std::to_string(values.size()));
    }
    for (std::size_t i = 0; i < width; ++i)
    {
      columns[i].push_back(values[i]);
    }
  }
  // Coordinates: the columns named x, y, z when there is a header, else the first two or three.
  auto column = [&](const char* name, std::size_t fallback) -> int {
    if (!names.empty())
    {
      const auto it = std::find(names.begin(), names.end(), name);
      return it == names.end() ? -1 : static_cast<int>(it - names.begin());
    }
    return fallback < width ? static_cast<int>(fallback) : -1;
  };
  const int cx = column("x", 0);
  const int cy = column("y", 1);
  const int cz = column("z", 2);
  if (width > 0 && (cx < 0 || cy < 0))
  {
    throw std::runtime_error(path + ": the header has no x and y columns");
  }
  const vtkIdType n = width == 0 ? 0 : static_cast<vtkIdType>(columns[0].size());
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(n);
  for (vtkIdType i = 0; i < n; ++i)
  {
    points->SetPoint(i, columns[cx][i], columns[cy][i], cz >= 0 ? columns[cz][i] : 0.0);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  vtkNew<vtkCellArray> verts;
  for (vtkIdType i = 0; i < n; ++i)
  {
    verts->InsertNextCell(1, &i);
  }
  poly->SetVerts(verts);
  for (std::size_t c = 0; c < names.size() && c < width; ++c)
  {
    if (static_cast<int>(c) == cx || static_cast<int>(c) == cy || static_cast<int>(c) == cz)
    {
      continue;
    }
    vtkNew<vtkDoubleArray> a;
    a->SetName(names[c].c_str());
    a->SetNumberOfValues(n);
    for (vtkIdType i = 0; i < n; ++i)
    {
      a->SetValue(i, columns[c][i]);
    }
    poly->GetPointData()->AddArray(a);
  }
  return poly;
}

void WriteTable(vtkDataSet* data, const std::string& path, bool csv)
{
  std::ofstream out(path);
  if (!out)
  {
    throw std::runtime_error("cannot write " + path);
  }
  vtkPointData* pd = data->GetPointData();
  std::vector<vtkDataArray*> arrays;
  if (csv)
  {
    out << "x,y,z";
    for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
    {
      vtkDataArray* array = pd->GetArray(a);
      if (!array || !array->GetName())
      {
        continue;
      }
      arrays.push_back(array);
      // A column name must survive being read back: no separators, line breaks or control
      // characters, and not empty (an unnamed column would shift every later one).
      std::string name = array->GetName();
      for (char& ch : name)
      {
        ch = ch == ',' || std::iscntrl(static_cast<unsigned char>(ch)) ? '_' : ch;
      }
      name = Trim(name).empty() ? "array" + std::to_string(arrays.size()) : name;
      const int nc = array->GetNumberOfComponents();
      for (int c = 0; c < nc; ++c)
      {
        out << ',' << name;
        if (nc > 1)
        {
          out << '_' << c;
        }
      }
    }
    out << '\n';
  }
  char buffer[64];
  const char sep = csv ? ',' : ' ';
  for (vtkIdType i = 0; i < data->GetNumberOfPoints(); ++i)
  {
    double p[3];
    data->GetPoint(i, p);
    for (int k = 0; k < 3; ++k)
    {
      std::snprintf(buffer, sizeof(buffer), "%.17g", p[k]);
      out << (k ? std::string(1, sep) : std::string()) << buffer;
    }
    for (vtkDataArray* array : arrays)
    {
      for (int c = 0; c < array->GetNumberOfComponents(); ++c)
      {
        std::snprintf(buffer, sizeof(buffer), "%.17g", array->GetComponent(i, c));
        out << sep << buffer;
      }
    }
    out << '\n';
  }
  if (!out)
  {
    throw std::runtime_error("error while writing " + path);
  }
}

// A polydata with the points and point data of any point set (cells become vertices).
vtkSmartPointer<vtkPolyData> AsPolyData(vtkDataSet* data)
{
  if (auto* poly = vtkPolyData::SafeDownCast(data))
  {
    return poly;
  }
  auto* pointSet = vtkPointSet::SafeDownCast(data);
  if (!pointSet)
  {
    throw std::runtime_error("this output is not a point set; write it as .vti or .vtu");
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(pointSet->GetPoints());
  poly->GetPointData()->ShallowCopy(pointSet->GetPointData());
  vtkNew<vtkCellArray> verts;
  for (vtkIdType i = 0; i < pointSet->GetNumberOfPoints(); ++i)
  {
    verts->InsertNextCell(1, &i);
  }
  poly->SetVerts(verts);
  return poly;
}

// PLY files are checked here, header and body, before VTK's reader sees them: that reader (the
// Stanford ply library) trusts the file, and a header without end_header, an unknown type, a list
// where it expects a number, a truncated body or a blank line inside an ASCII body make it read
// freed or unallocated memory, or abort on an assert (found by tests/fuzz/FuzzCliInput.cxx).
// What passes is exactly what it reads safely; everything else fails with the line or element
// that is wrong.
namespace ply
{

struct Type
{
  int size = 0;   // bytes
  char kind = 0;  // 'i' signed integer, 'u' unsigned integer, 'f' floating point
};

// The type names VTK's reader knows, nothing else.
bool LookUpType(const std::string& name, Type& type)
{
  static const struct
  {
    const char* name;
    Type type;
  } table[] = { { "char", { 1, 'i' } }, { "int8", { 1, 'i' } }, { "uchar", { 1, 'u' } }, { "uint8", { 1, 'u' } },
    { "short", { 2, 'i' } }, { "int16", { 2, 'i' } }, { "ushort", { 2, 'u' } }, { "uint16", { 2, 'u' } },
    { "int", { 4, 'i' } }, { "int32", { 4, 'i' } }, { "uint", { 4, 'u' } }, { "uint32", { 4, 'u' } },
    { "float", { 4, 'f' } }, { "float32", { 4, 'f' } }, { "double", { 8, 'f' } }, { "float64", { 8, 'f' } } };
  for (const auto& entry : table)
  {
    if (name == entry.name)
    {
      type = entry.type;
      return true;
    }
  }
  return false;
}

struct Property
{
  std::string name;
  bool list = false;
  Type count; // list length type
  Type item;
};

struct Element
{
  std::string name;
  long long count = 0;
  std::vector<Property> properties;
};

std::vector<std::string> Words(const std::string& line)
{
  std::vector<std::string> words;
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
      words.push_back(line.substr(begin, i - begin));
    }
  }
  return words;
}

bool IsCount(const std::string& word, long long limit, long long& value)
{
  if (word.empty() || word.size() > 12 ||
    !std::all_of(word.begin(), word.end(), [](unsigned char c) { return std::isdigit(c) != 0; }))
  {
    return false;
  }
  value = std::stoll(word);
  return value <= limit;
}

bool IsNumber(const std::string& word)
{
  char* end = nullptr;
  std::strtod(word.c_str(), &end);
  return !word.empty() && end == word.c_str() + word.size();
}

// An unsigned or signed integer of @p type at @p p (the count of a binary list).
long long DecodeCount(const unsigned char* p, const Type& type, bool bigEndian)
{
  unsigned long long bits = 0;
  for (int b = 0; b < type.size; ++b)
  {
    bits |= static_cast<unsigned long long>(p[bigEndian ? type.size - 1 - b : b]) << (8 * b);
  }
  if (type.kind == 'i' && type.size < 8 && (bits >> (8 * type.size - 1)) != 0)
  {
    return -1; // negative
  }
  return static_cast<long long>(bits);
}

// A value of @p type at @p p, as a double (the face indices' range check).
double DecodeValue(const unsigned char* p, const Type& type, bool bigEndian)
{
  unsigned long long bits = 0;
  for (int b = 0; b < type.size; ++b)
  {
    bits |= static_cast<unsigned long long>(p[bigEndian ? type.size - 1 - b : b]) << (8 * b);
  }
  if (type.kind == 'f')
  {
    if (type.size == 4)
    {
      float f = 0.0f;
      const auto u = static_cast<std::uint32_t>(bits);
      std::memcpy(&f, &u, sizeof f);
      return f;
    }
    double d = 0.0;
    std::memcpy(&d, &bits, sizeof d);
    return d;
  }
  if (type.kind == 'i' && (bits >> (8 * type.size - 1)) != 0)
  {
    return static_cast<double>(static_cast<long long>(bits) - (1LL << (8 * type.size)));
  }
  return static_cast<double>(bits);
}

// Face lists VTK's reader turns into cells: their items index the vertices.
bool IsFaceIndexList(const Element& e, const Property& p)
{
  return e.name == "face" && p.list && (p.name == "vertex_indices" || p.name == "vertex_index");
}

// Longest line VTK's ply library reads in one piece (its BIG_STRING buffer is 4096 bytes).
constexpr std::size_t MaxLine = 4000;

void Validate(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  const std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string where = path + ": not a PLY file VTK can read safely: ";
  std::size_t pos = 0;
  std::size_t lineNumber = 0;
  bool terminated = false; // the last line read ended with '\n'
  // The next line without its '\n'; false at the end of the data.
  auto nextLine = [&](std::string& line) {
    if (pos >= data.size())
    {
      return false;
    }
    std::size_t end = data.find('\n', pos);
    terminated = end != std::string::npos;
    if (!terminated)
    {
      end = data.size();
    }
    line.assign(data, pos, end - pos);
    pos = end < data.size() ? end + 1 : data.size();
    ++lineNumber;
    return true;
  };
  auto fail = [&](const std::string& what) {
    throw std::runtime_error(where + "line " + std::to_string(lineNumber) + ": " + what);
  };

  // Header.
  std::string line;
  std::string format;
  std::vector<Element> elements;
  bool ended = false;
  while (!ended && nextLine(line))
  {
    if (line.size() > MaxLine)
    {
      fail("header line longer than " + std::to_string(MaxLine) + " characters");
    }
    // VTK's reader asserts when a line it reads ends at the end of the file instead of a '\n'.
    if (!terminated)
    {
      fail("the header ends without a line end");
    }
    // VTK's header parser stops a line at a NUL and miscounts its words (a crash): header lines
    // are printable text.
    if (std::any_of(line.begin(), line.end(),
          [](char c) { return (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\r') || c == 0x7f; }))
    {
      fail("control character in the header");
    }
    const std::vector<std::string> w = Words(line);
    if (lineNumber == 1)
    {
      if (w.size() != 1 || w[0] != "ply")
      {
        fail("the first line must be 'ply'");
      }
      continue;
    }
    if (w.empty())
    {
      fail("blank line in the header");
    }
    if (w[0] == "comment" || w[0] == "obj_info")
    {
      continue;
    }
    if (w[0] == "format")
    {
      if (!format.empty() || w.size() != 3 ||
        (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian") || w[2] != "1.0")
      {
        fail("expected one 'format ascii|binary_little_endian|binary_big_endian 1.0'");
      }
      format = w[1];
    }
    else if (w[0] == "element")
    {
      Element e;
      if (w.size() != 3 || !IsCount(w[2], 2147483647LL, e.count))
      {
        fail("expected 'element NAME COUNT' with a count below 2^31");
      }
      e.name = w[1];
      for (const Element& other : elements)
      {
        if (other.name == e.name)
        {
          fail("element '" + e.name + "' declared twice");
        }
      }
      elements.push_back(e);
    }
    else if (w[0] == "property")
    {
      if (elements.empty())
      {
        fail("a property before any element");
      }
      Property p;
      if (w.size() == 3 && LookUpType(w[1], p.item))
      {
        p.name = w[2];
      }
      else if (w.size() == 5 && w[1] == "list" && LookUpType(w[2], p.count) && p.count.kind != 'f' &&
        LookUpType(w[3], p.item))
      {
        p.list = true;
        p.name = w[4];
      }
      else
      {
        fail("expected 'property TYPE NAME' or 'property list INTEGER_TYPE TYPE NAME' with a known type");
      }
      elements.back().properties.push_back(p);
    }
    else if (w[0] == "end_header" && w.size() == 1)
    {
      ended = true;
    }
    else
    {
      fail("unknown header line '" + w[0] + "'");
    }
  }
  if (!ended)
  {
    fail("the header has no end_header");
  }
  if (format.empty())
  {
    fail("the header has no format line");
  }

  // The properties VTK's reader takes, with the shape it takes them in.
  const Element* vertex = nullptr;
  for (const Element& e : elements)
  {
    static const char* const vertexScalars[] = { "x", "y", "z", "u", "v", "texture_u", "texture_v", "nx", "ny",
      "nz", "red", "green", "blue", "alpha", "diffuse_red", "diffuse_green", "diffuse_blue" };
    static const char* const faceScalars[] = { "intensity", "red", "green", "blue", "alpha" };
    static const char* const faceLists[] = { "vertex_indices", "vertex_index", "texcoord" };
    vertex = e.name == "vertex" ? &e : vertex;
    if (e.count > 0 && e.properties.empty())
    {
      throw std::runtime_error(where + "element '" + e.name + "' has rows but no properties");
    }
    for (const Property& p : e.properties)
    {
      auto among = [&](const auto& names) {
        return std::any_of(std::begin(names), std::end(names), [&](const char* n) { return p.name == n; });
      };
      const bool mustBeScalar = (e.name == "vertex" && among(vertexScalars)) || (e.name == "face" && among(faceScalars));
      const bool mustBeList = e.name == "face" && among(faceLists);
      if ((mustBeScalar && p.list) || (mustBeList && !p.list))
      {
        throw std::runtime_error(where + "property '" + p.name + "' of element '" + e.name + "' must " +
          (p.list ? "not " : "") + "be a list");
      }
    }
  }
  auto has = [&](const char* name) {
    return vertex && std::any_of(vertex->properties.begin(), vertex->properties.end(),
                       [&](const Property& p) { return p.name == name; });
  };
  if (!has("x") || !has("y") || !has("z"))
  {
    throw std::runtime_error(where + "no 'vertex' element with x, y and z properties");
  }
  // VTK's reader reads the vertex list of every face row whether or not the file declares one:
  // without it, it reads an uninitialized pointer (a crash).
  for (const Element& e : elements)
  {
    if (e.name == "face" && e.count > 0 &&
      std::none_of(e.properties.begin(), e.properties.end(), [&](const Property& p) { return IsFaceIndexList(e, p); }))
    {
      throw std::runtime_error(where + "element 'face' has no 'vertex_indices' (or 'vertex_index') list");
    }
  }
  // A face index outside the vertices made VTK's reader read outside its points (a crash).
  const double vertexCount = static_cast<double>(vertex->count);
  auto checkIndex = [&](double v, const Element& e, long long r) {
    if (!(v >= 0.0 && v < vertexCount))
    {
      throw std::runtime_error(where + "'" + e.name + "' row " + std::to_string(r) + ": vertex index " +
        std::to_string(v) + " outside [0, " + std::to_string(vertex->count) + ")");
    }
  };

  // Body: every element row complete, with a number for every value.
  if (format == "ascii")
  {
    for (const Element& e : elements)
    {
      for (long long r = 0; r < e.count; ++r)
      {
        if (!nextLine(line))
        {
          throw std::runtime_error(where + "the file ends after " + std::to_string(r) + " of " +
            std::to_string(e.count) + " '" + e.name + "' rows");
        }
        if (line.size() > MaxLine)
        {
          fail("longer than " + std::to_string(MaxLine) + " characters");
        }
        if (!terminated)
        {
          fail("'" + e.name + "' row " + std::to_string(r) + " ends without a line end (the file is cut off?)");
        }
        const std::vector<std::string> w = Words(line);
        std::size_t k = 0;
        for (const Property& p : e.properties)
        {
          long long n = 1;
          if (p.list && (k >= w.size() || !IsCount(w[k++], 1000000, n)))
          {
            fail("'" + e.name + "' row " + std::to_string(r) + ": the length of list '" + p.name +
              "' must be an integer in [0, 1e6]");
          }
          for (long long i = 0; i < n; ++i, ++k)
          {
            if (k >= w.size() || !IsNumber(w[k]))
            {
              fail("'" + e.name + "' row " + std::to_string(r) + ": missing or non-numeric value of '" + p.name + "'");
            }
            if (IsFaceIndexList(e, p))
            {
              checkIndex(std::strtod(w[k].c_str(), nullptr), e, r);
            }
          }
        }
        if (k != w.size())
        {
          fail("'" + e.name + "' row " + std::to_string(r) + ": " + std::to_string(w.size() - k) + " values too many");
        }
      }
    }
    return;
  }
  const bool bigEndian = format == "binary_big_endian";
  const auto* bytes = reinterpret_cast<const unsigned char*>(data.data());
  for (const Element& e : elements)
  {
    for (long long r = 0; r < e.count; ++r)
    {
      for (const Property& p : e.properties)
      {
        long long n = 1;
        if (p.list)
        {
          if (data.size() - pos < static_cast<std::size_t>(p.count.size))
          {
            n = -2;
          }
          else
          {
            n = DecodeCount(bytes + pos, p.count, bigEndian);
            pos += static_cast<std::size_t>(p.count.size);
          }
          if (n < 0 || n > 1000000)
          {
            throw std::runtime_error(where + "'" + e.name + "' row " + std::to_string(r) + ": list '" + p.name +
              (n == -2 ? "' is cut off" : "' has a length outside [0, 1e6]"));
          }
        }
        const std::size_t need = static_cast<std::size_t>(n) * static_cast<std::size_t>(p.item.size);
        if (data.size() - pos < need)
        {
          throw std::runtime_error(where + "the file ends inside '" + e.name + "' row " + std::to_string(r) +
            " of " + std::to_string(e.count));
        }
        if (IsFaceIndexList(e, p))
        {
          for (long long i = 0; i < n; ++i)
          {
            checkIndex(DecodeValue(bytes + pos + static_cast<std::size_t>(i * p.item.size), p.item, bigEndian), e, r);
          }
        }
        pos += need;
      }
    }
  }
}

} // namespace ply

// VTK XML files (.vtp .vtu .vti) are checked here, before VTK's readers see them. Those readers
// trust the file: the counts of a Piece (NumberOfPoints, NumberOfCells, Extent), the size header
// in front of every binary array (block count, block sizes, compressed sizes) and the cell offsets
// size their allocations and index their buffers, so one corrupted number makes them allocate
// gigabytes, divide by zero or read outside a buffer (found by tests/fuzz/FuzzCliInput.cxx).
// What passes is consistent: every count fits in what the file can hold, every size header agrees
// with the counts and with the bytes actually present, every cell index stays inside its arrays.
// Everything else fails with the element or array that is wrong. The markup is parsed here too
// (no DTDs or CDATA, which VTK's files never use), exactly as far as VTK's parser reads it.
namespace vtkxml
{

enum class Compressor
{
  None,
  ZLib,
  LZ4,
  LZMA
};

const char* CompressorName(Compressor c)
{
  switch (c)
  {
    case Compressor::ZLib:
      return "vtkZLibDataCompressor";
    case Compressor::LZ4:
      return "vtkLZ4DataCompressor";
    case Compressor::LZMA:
      return "vtkLZMADataCompressor";
    case Compressor::None:
      break;
  }
  return "no compressor";
}

// The most bytes one compressed byte can decompress to, the bound on every decompressed size.
// Deflate codes a 258-byte match in 2 bits at best: 1032:1. An LZ4 sequence needs one more byte
// for every 255 bytes of match length: < 255:1. LZMA2 (xz, what vtkLZMADataCompressor writes)
// codes a 273-byte repeat in about 14 binary decisions whose probability is at most 2017/2048
// (11-bit probabilities adapted by 1/32), 0.31 bit, i.e. ~7000:1, less its chunk headers
// (`xz -9e` reaches 6870:1 on zeros); 8192 keeps a margin.
std::uint64_t MaxRatio(Compressor c)
{
  switch (c)
  {
    case Compressor::ZLib:
      return 1032;
    case Compressor::LZ4:
      return 255;
    case Compressor::LZMA:
      return 8192;
    case Compressor::None:
      break;
  }
  return 1;
}

// Most components an array may have: VTK loops over them for component names before reading.
constexpr std::uint64_t MaxComponents = 65535;
// An image's points are implicit (its Extent): an image of up to 2^20 points is accepted whatever
// its file size; beyond, the file must hold data for them.
constexpr std::uint64_t SmallImage = std::uint64_t(1) << 20;

std::uint64_t MulSat(std::uint64_t a, std::uint64_t b)
{
  std::uint64_t r = 0;
  return __builtin_mul_overflow(a, b, &r) ? std::numeric_limits<std::uint64_t>::max() : r;
}

std::uint64_t AddSat(std::uint64_t a, std::uint64_t b)
{
  std::uint64_t r = 0;
  return __builtin_add_overflow(a, b, &r) ? std::numeric_limits<std::uint64_t>::max() : r;
}

bool IsSpace(char c)
{
  return c == ' ' || c == '\t' || c == '\n' || c == '\r';
}

// A non-negative decimal integer, the whole value (VTK's attribute parser would read "12abc" or
// "1e15" as their leading digits).
bool ParseUnsigned(const std::string& text, std::uint64_t& value)
{
  const std::string t = Trim(text);
  if (t.empty() || t.size() > 18 ||
    !std::all_of(t.begin(), t.end(), [](unsigned char c) { return std::isdigit(c) != 0; }))
  {
    return false;
  }
  value = std::stoull(t);
  return true;
}

bool ParseSigned(const std::string& text, long long& value)
{
  const std::string t = Trim(text);
  const bool negative = !t.empty() && t[0] == '-';
  std::uint64_t magnitude = 0;
  if (!ParseUnsigned(negative ? t.substr(1) : t, magnitude) || (negative && t.size() == 1))
  {
    return false;
  }
  value = negative ? -static_cast<long long>(magnitude) : static_cast<long long>(magnitude);
  return true;
}

struct Attribute
{
  std::string name;
  std::string value;
};

struct Element
{
  std::string name;
  std::vector<Attribute> attributes;
  std::size_t begin = 0;   // offset of its '<'
  std::size_t content = 0; // first byte after the '>' of its start tag (VTK's inline data start there)
  std::size_t textEnd = 0; // the next '<' after content: the end of its inline data
  std::vector<std::size_t> children;

  const std::string* Find(const std::string& key) const
  {
    for (const Attribute& a : attributes)
    {
      if (a.name == key)
      {
        return &a.value;
      }
    }
    return nullptr;
  }
};

struct Document
{
  std::vector<Element> elements; // elements[0] is the root
  bool appended = false;         // an <AppendedData> section
  bool appendedRaw = false;      // encoding="raw", else base64
  std::size_t appendedBegin = 0; // its first byte, after the '_'
};

struct File
{
  std::string path;
  std::string data;
  Document doc;
  Compressor compressor = Compressor::None;
  std::uint64_t headerSize = 4; // bytes per size-header word (header_type)
  bool bigEndian = false;
  std::uint64_t budget = 0; // most bytes all arrays together can hold (file size x MaxRatio)
  std::uint64_t used = 0;   // bytes the arrays checked so far hold

  [[noreturn]] void Fail(const std::string& what) const
  {
    throw std::runtime_error(path + ": not a VTK XML file pss can read safely: " + what);
  }

  [[noreturn]] void FailAt(std::size_t offset, const std::string& what) const
  {
    offset = std::min(offset, data.size());
    const auto line = 1 + std::count(data.begin(), data.begin() + static_cast<std::ptrdiff_t>(offset), '\n');
    Fail("line " + std::to_string(line) + ": " + what);
  }

  const Element& At(std::size_t index) const { return doc.elements[index]; }
};

// ---------------------------------------------------------------------------------------------
// Markup

bool IsNameChar(unsigned char c)
{
  return std::isalnum(c) || c == '_' || c == ':' || c == '-' || c == '.' || c >= 0x80;
}

std::size_t SkipSpace(const std::string& s, std::size_t pos, std::size_t end)
{
  while (pos < end && IsSpace(s[pos]))
  {
    ++pos;
  }
  return pos;
}

std::string ReadName(const File& f, std::size_t& pos, std::size_t end)
{
  const std::size_t begin = pos;
  while (pos < end && IsNameChar(static_cast<unsigned char>(f.data[pos])))
  {
    ++pos;
  }
  if (pos == begin || std::isdigit(static_cast<unsigned char>(f.data[begin])) || f.data[begin] == '-' ||
    f.data[begin] == '.')
  {
    f.FailAt(begin, "expected an element or attribute name");
  }
  return f.data.substr(begin, pos - begin);
}

void AppendUtf8(std::string& out, unsigned long code)
{
  if (code < 0x80)
  {
    out += static_cast<char>(code);
  }
  else if (code < 0x800)
  {
    out += static_cast<char>(0xC0 | (code >> 6));
    out += static_cast<char>(0x80 | (code & 0x3F));
  }
  else if (code < 0x10000)
  {
    out += static_cast<char>(0xE0 | (code >> 12));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  }
  else
  {
    out += static_cast<char>(0xF0 | (code >> 18));
    out += static_cast<char>(0x80 | ((code >> 12) & 0x3F));
    out += static_cast<char>(0x80 | ((code >> 6) & 0x3F));
    out += static_cast<char>(0x80 | (code & 0x3F));
  }
}

// An attribute value as the XML parser hands it to VTK: references decoded, line breaks and tabs
// made spaces (so a count parsed here is the count VTK gets).
std::string DecodeValue(const File& f, const std::string& raw, std::size_t at)
{
  std::string out;
  for (std::size_t i = 0; i < raw.size(); ++i)
  {
    const char c = raw[i];
    if (c != '&')
    {
      out += c == '\t' || c == '\n' || c == '\r' ? ' ' : c;
      continue;
    }
    const std::size_t semi = raw.find(';', i);
    if (semi == std::string::npos || semi - i > 12)
    {
      f.FailAt(at, "an '&' in an attribute value that is not a reference");
    }
    const std::string ref = raw.substr(i + 1, semi - i - 1);
    static const std::pair<const char*, char> named[] = { { "lt", '<' }, { "gt", '>' }, { "amp", '&' },
      { "quot", '"' }, { "apos", '\'' } };
    const auto it = std::find_if(std::begin(named), std::end(named), [&](const auto& n) { return ref == n.first; });
    if (it != std::end(named))
    {
      out += it->second;
    }
    else if (ref.size() >= 2 && ref[0] == '#')
    {
      const bool hex = ref[1] == 'x';
      const std::string digits = ref.substr(hex ? 2 : 1);
      char* end = nullptr;
      const unsigned long code = std::strtoul(digits.c_str(), &end, hex ? 16 : 10);
      if (digits.empty() || *end != '\0' || code == 0 || code > 0x10FFFF ||
        !std::all_of(digits.begin(), digits.end(), [](unsigned char d) { return std::isxdigit(d) != 0; }))
      {
        f.FailAt(at, "bad character reference &" + ref + ";");
      }
      AppendUtf8(out, code);
    }
    else
    {
      f.FailAt(at, "unknown entity &" + ref + ";");
    }
    i = semi;
  }
  return out;
}

std::string ReadValue(const File& f, std::size_t& pos, std::size_t end)
{
  if (pos >= end || (f.data[pos] != '"' && f.data[pos] != '\''))
  {
    f.FailAt(pos, "expected a quoted attribute value");
  }
  const char quote = f.data[pos];
  const std::size_t begin = pos + 1;
  const std::size_t close = f.data.find(quote, begin);
  if (close == std::string::npos || close >= end)
  {
    f.FailAt(pos, "an attribute value without its closing quote");
  }
  const std::string raw = f.data.substr(begin, close - begin);
  // VTK finds where an array's inline data start by the first '>' after its '<': a '>' inside a
  // value would make it read the rest of the tag as data.
  if (raw.find_first_of("<>") != std::string::npos)
  {
    f.FailAt(begin, "'<' or '>' inside an attribute value");
  }
  pos = close + 1;
  return DecodeValue(f, raw, begin);
}

// The start tag at @p pos (its '<'): adds the element under the innermost open one, returns its
// index, leaves @p pos after the '>'.
std::size_t StartTag(const File& f, Document& doc, std::size_t& pos, std::size_t end, std::vector<std::size_t>& open)
{
  Element e;
  e.begin = pos++;
  e.name = ReadName(f, pos, end);
  bool selfClosing = false;
  while (true)
  {
    const std::size_t before = pos;
    pos = SkipSpace(f.data, pos, end);
    if (pos >= end)
    {
      f.FailAt(e.begin, "the start tag <" + e.name + " is not closed (the file is cut off?)");
    }
    if (f.data[pos] == '>')
    {
      ++pos;
      break;
    }
    if (f.data[pos] == '/')
    {
      if (pos + 1 >= end || f.data[pos + 1] != '>')
      {
        f.FailAt(pos, "expected '/>' in <" + e.name + ">");
      }
      pos += 2;
      selfClosing = true;
      break;
    }
    if (pos == before)
    {
      f.FailAt(pos, "expected a space before an attribute of <" + e.name + ">");
    }
    Attribute a;
    a.name = ReadName(f, pos, end);
    pos = SkipSpace(f.data, pos, end);
    if (pos >= end || f.data[pos] != '=')
    {
      f.FailAt(pos, "expected '=' after attribute " + a.name + " of <" + e.name + ">");
    }
    pos = SkipSpace(f.data, pos + 1, end);
    a.value = ReadValue(f, pos, end);
    if (e.Find(a.name))
    {
      f.FailAt(pos, "attribute " + a.name + " repeated in <" + e.name + ">");
    }
    e.attributes.push_back(std::move(a));
  }
  e.content = pos;
  e.textEnd = std::min(f.data.find('<', pos), f.data.size());
  const std::size_t index = doc.elements.size();
  if (!open.empty())
  {
    doc.elements[open.back()].children.push_back(index);
  }
  doc.elements.push_back(std::move(e));
  if (!selfClosing)
  {
    open.push_back(index);
  }
  return index;
}

// Skips "<!--...-->" or "<?...?>" at @p pos; false when there is neither.
bool SkipCommentOrInstruction(const File& f, std::size_t& pos, std::size_t end)
{
  const std::string& s = f.data;
  const char* close = s.compare(pos, 4, "<!--") == 0 ? "-->" : s.compare(pos, 2, "<?") == 0 ? "?>" : nullptr;
  if (!close)
  {
    return false;
  }
  const std::size_t at = s.find(close, pos + 2);
  if (at == std::string::npos || at + std::strlen(close) > end)
  {
    f.FailAt(pos, std::string("a comment or processing instruction without its '") + close + "'");
  }
  pos = at + std::strlen(close);
  return true;
}

// The document, read the way vtkXMLDataParser reads it: it stops at the first "<AppendedData"
// anywhere in the file (raw data follow), takes that element's start tag and ends the document
// there; the appended data start after the '_' that follows the tag.
Document ParseMarkup(const File& f)
{
  Document doc;
  const std::string& s = f.data;
  const std::size_t appendedTag = s.find("<AppendedData");
  const std::size_t end = appendedTag == std::string::npos ? s.size() : appendedTag;
  std::vector<std::size_t> open;
  bool rootDone = false;
  std::size_t pos = s.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
  while (true)
  {
    const std::size_t lt = std::min(s.find('<', pos), end);
    if (open.empty() && std::any_of(s.begin() + static_cast<std::ptrdiff_t>(pos),
                          s.begin() + static_cast<std::ptrdiff_t>(lt), [](char c) { return !IsSpace(c); }))
    {
      f.FailAt(pos, rootDone ? "text after the root element" : "text before the root element");
    }
    if (lt >= end)
    {
      break;
    }
    pos = lt;
    if (SkipCommentOrInstruction(f, pos, end))
    {
      continue;
    }
    if (s.compare(pos, 2, "<!") == 0)
    {
      f.FailAt(pos, "unsupported markup (a DOCTYPE or CDATA section)");
    }
    if (s.compare(pos, 2, "</") == 0)
    {
      pos += 2;
      const std::string name = ReadName(f, pos, end);
      pos = SkipSpace(s, pos, end);
      if (pos >= end || s[pos] != '>')
      {
        f.FailAt(pos, "the end tag </" + name + " is not closed");
      }
      if (open.empty() || doc.elements[open.back()].name != name)
      {
        f.FailAt(pos, "</" + name + "> does not close " +
            (open.empty() ? std::string("any element") : "<" + doc.elements[open.back()].name + ">"));
      }
      open.pop_back();
      rootDone = open.empty();
      ++pos;
      continue;
    }
    if (rootDone)
    {
      f.FailAt(pos, "a second root element");
    }
    StartTag(f, doc, pos, end, open);
  }
  if (doc.elements.empty())
  {
    f.Fail("no root element");
  }
  if (appendedTag == std::string::npos)
  {
    if (!open.empty())
    {
      f.FailAt(s.size(), "the file ends inside <" + doc.elements[open.back()].name + "> (cut off?)");
    }
    return doc;
  }
  if (open.size() != 1)
  {
    f.FailAt(appendedTag, "<AppendedData> must come right inside <VTKFile>, after every other element is closed");
  }
  pos = appendedTag;
  const std::size_t index = StartTag(f, doc, pos, s.size(), open);
  // VTK stops at "<AppendedData" whatever follows; another element (<AppendedDataX>) would leave
  // it without appended data, reading "appended" arrays from the start of the file.
  if (doc.elements[index].name != "AppendedData")
  {
    f.FailAt(appendedTag, "<" + doc.elements[index].name + "> where VTK expects <AppendedData>");
  }
  const std::string* encoding = doc.elements[index].Find("encoding");
  if (encoding && *encoding != "raw" && *encoding != "base64")
  {
    f.FailAt(appendedTag, "<AppendedData encoding=\"" + *encoding + "\">: expected raw or base64");
  }
  pos = SkipSpace(s, pos, s.size());
  if (pos >= s.size() || s[pos] != '_')
  {
    f.FailAt(pos, "the appended data do not start with '_'");
  }
  doc.appended = true;
  doc.appendedRaw = encoding && *encoding == "raw";
  doc.appendedBegin = pos + 1;
  return doc;
}

std::vector<const Element*> Children(const File& f, const Element& parent, const char* name)
{
  std::vector<const Element*> out;
  for (const std::size_t c : parent.children)
  {
    if (f.At(c).name == name)
    {
      out.push_back(&f.At(c));
    }
  }
  return out;
}

// The one <name> child of @p parent, or null; two are refused (which one VTK uses differs).
const Element* OnlyChild(const File& f, const Element& parent, const char* name, const std::string& where)
{
  const std::vector<const Element*> found = Children(f, parent, name);
  if (found.size() > 1)
  {
    f.Fail(where + ": more than one <" + name + ">");
  }
  return found.empty() ? nullptr : found[0];
}

// ---------------------------------------------------------------------------------------------
// Encoded bytes: inline base64, appended base64 or appended raw

int Base64Digit(unsigned char c)
{
  if (c >= 'A' && c <= 'Z')
    return c - 'A';
  if (c >= 'a' && c <= 'z')
    return c - 'a' + 26;
  if (c >= '0' && c <= '9')
    return c - '0' + 52;
  if (c == '+')
    return 62;
  if (c == '/')
    return 63;
  return -1;
}

// Where an array's encoded data are, as VTK reads them.
struct Stream
{
  std::size_t begin = 0; // first character (base64) or byte (raw)
  std::size_t end = 0;   // end of what can be read
  bool base64 = true;
};

// Most bytes @p s can decode to.
std::uint64_t Capacity(const Stream& s)
{
  const std::uint64_t n = s.end > s.begin ? s.end - s.begin : 0;
  return s.base64 ? n / 4 * 3 : n;
}

// Decodes up to @p count bytes from the start of @p s the way VTK's stream does (groups of four
// characters, '=' padding ends the stream) and returns how many it got: fewer when the text ends,
// holds a character that is not base64, or is padded early. Appends them to @p out when given.
std::uint64_t Read(const File& f, const Stream& s, std::uint64_t count, std::vector<unsigned char>* out)
{
  if (!s.base64)
  {
    const std::uint64_t n = std::min(count, Capacity(s));
    if (out && n > 0)
    {
      out->insert(out->end(), f.data.begin() + static_cast<std::ptrdiff_t>(s.begin),
        f.data.begin() + static_cast<std::ptrdiff_t>(s.begin + n));
    }
    return n;
  }
  std::uint64_t n = 0;
  for (std::size_t pos = s.begin; n < count && s.end >= pos + 4; pos += 4)
  {
    const auto* g = reinterpret_cast<const unsigned char*>(f.data.data() + pos);
    const int d0 = Base64Digit(g[0]);
    const int d1 = Base64Digit(g[1]);
    const int d2 = g[2] == '=' ? -2 : Base64Digit(g[2]);
    const int d3 = g[3] == '=' ? -2 : Base64Digit(g[3]);
    if (d0 < 0 || d1 < 0 || d2 == -1 || d3 == -1 || (d2 == -2 && d3 != -2))
    {
      break;
    }
    const unsigned char bytes[3] = { static_cast<unsigned char>((d0 << 2) | (d1 >> 4)),
      static_cast<unsigned char>(((d1 & 15) << 4) | (d2 < 0 ? 0 : d2 >> 2)),
      static_cast<unsigned char>(((d2 < 0 ? 0 : d2 & 3) << 6) | (d3 < 0 ? 0 : d3)) };
    const std::uint64_t decoded = d2 < 0 ? 1 : d3 < 0 ? 2 : 3;
    const std::uint64_t take = std::min(decoded, count - n);
    if (out)
    {
      out->insert(out->end(), bytes, bytes + take);
    }
    n += take;
    if (decoded < 3)
    {
      break;
    }
  }
  return n;
}

std::uint64_t Word(const std::vector<unsigned char>& bytes, std::size_t index, std::uint64_t size, bool bigEndian)
{
  std::uint64_t v = 0;
  for (std::uint64_t b = 0; b < size; ++b)
  {
    v |= static_cast<std::uint64_t>(bytes[index * size + (bigEndian ? size - 1 - b : b)]) << (8 * b);
  }
  return v;
}

// ---------------------------------------------------------------------------------------------
// Arrays

struct ArrayType
{
  const char* name;
  std::uint64_t size; // bytes per value
  char kind;          // 'i' signed, 'u' unsigned, 'f' floating point, 's' string (bytes)
};

const ArrayType* LookUpArrayType(const std::string& name)
{
  static const ArrayType types[] = { { "Int8", 1, 'i' }, { "UInt8", 1, 'u' }, { "Int16", 2, 'i' },
    { "UInt16", 2, 'u' }, { "Int32", 4, 'i' }, { "UInt32", 4, 'u' }, { "Int64", 8, 'i' }, { "UInt64", 8, 'u' },
    { "Float32", 4, 'f' }, { "Float64", 8, 'f' }, { "String", 1, 's' } };
  for (const ArrayType& t : types)
  {
    if (name == t.name)
    {
      return &t;
    }
  }
  return nullptr;
}

struct Array
{
  const Element* element = nullptr;
  std::string label; // for messages: "piece 0 <PointData> array 'Normals'"
  const ArrayType* type = nullptr;
  std::uint64_t components = 1;
  bool ascii = false;
  bool appended = false;
};

// How many values an array must hold, and why (for the message when it does not).
struct Expected
{
  std::uint64_t values = 0;
  std::string why;
};

// The attributes of a <DataArray> (or <Array>) element, checked.
Array Describe(const File& f, const Element& e, const std::string& label)
{
  Array a;
  a.element = &e;
  const std::string* name = e.Find("Name");
  a.label = label + (name ? " '" + *name + "'" : std::string());
  if (e.name != "DataArray" && e.name != "Array")
  {
    f.Fail(a.label + ": <" + e.name + "> where a <DataArray> belongs");
  }
  const std::string* type = e.Find("type");
  a.type = type ? LookUpArrayType(*type) : nullptr;
  if (!a.type)
  {
    f.Fail(a.label + ": " + (type ? "unknown type '" + *type + "'" : std::string("no type")) +
      " (known: Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32, Float64, String)");
  }
  if (const std::string* nc = e.Find("NumberOfComponents"))
  {
    if (!ParseUnsigned(*nc, a.components) || a.components < 1 || a.components > MaxComponents)
    {
      f.Fail(a.label + ": NumberOfComponents=\"" + *nc + "\" is not an integer in [1, " +
        std::to_string(MaxComponents) + "]");
    }
  }
  if (e.Find("TimeStep"))
  {
    f.Fail(a.label + ": arrays with a TimeStep are not supported");
  }
  const std::string* format = e.Find("format");
  if (!format || (*format != "ascii" && *format != "binary" && *format != "appended"))
  {
    f.Fail(a.label + ": format=\"" + (format ? *format : std::string()) + "\", expected ascii, binary or appended");
  }
  a.ascii = *format == "ascii";
  a.appended = *format == "appended";
  // VTK reads appended data whenever there is an offset, whatever the format says.
  if (a.appended != (e.Find("offset") != nullptr))
  {
    f.Fail(a.label +
      (a.appended ? ": format=\"appended\" without an offset" : ": an offset but format=\"" + *format + "\""));
  }
  // VTK rebuilds quadrature-scheme dictionaries from sizes written in the file, unchecked.
  for (const std::size_t c : e.children)
  {
    const std::string* key = f.At(c).Find("location");
    if (f.At(c).name == "InformationKey" && key && *key == "vtkQuadratureSchemeDefinition")
    {
      f.Fail(a.label + ": quadrature-scheme information keys are not supported");
    }
  }
  return a;
}

// Visits the words of an ASCII array's inline text that VTK would read as its values (it stops
// at the first word it cannot parse as a value of the array's type, or at the next '<') until
// @p visit returns false; returns how many it visited.
template <class Visit>
std::uint64_t AsciiValues(const File& f, const Array& a, Visit&& visit)
{
  const Element& e = *a.element;
  std::uint64_t count = 0;
  std::size_t pos = e.content;
  while (true)
  {
    pos = SkipSpace(f.data, pos, e.textEnd);
    std::size_t stop = pos;
    while (stop < e.textEnd && !IsSpace(f.data[stop]))
    {
      ++stop;
    }
    const std::string w = f.data.substr(pos, stop - pos);
    long long i = 0;
    double d = 0.0;
    if (pos >= e.textEnd || (a.type->kind == 'f' ? !ParseDouble(w, d) : !ParseSigned(w, i)) || !visit(w))
    {
      return count;
    }
    ++count;
    pos = stop;
  }
}

// Where the binary data of @p a are.
Stream Locate(const File& f, const Array& a)
{
  Stream s;
  if (!a.appended)
  {
    s.begin = SkipSpace(f.data, a.element->content, f.data.size());
    s.end = std::max(s.begin, a.element->textEnd);
    return s;
  }
  if (!f.doc.appended)
  {
    f.Fail(a.label + ": format=\"appended\" but the file has no <AppendedData>");
  }
  const std::string& text = *a.element->Find("offset");
  std::uint64_t offset = 0;
  if (!ParseUnsigned(text, offset))
  {
    f.Fail(a.label + ": offset=\"" + text + "\" is not a non-negative integer");
  }
  const std::uint64_t length = f.data.size() - f.doc.appendedBegin;
  if (offset >= length)
  {
    f.Fail(a.label + ": offset " + text + " is past the end of the appended data (" + std::to_string(length) +
      " bytes)");
  }
  s.begin = f.doc.appendedBegin + offset;
  s.end = f.data.size();
  s.base64 = !f.doc.appendedRaw;
  return s;
}

// An array's binary size header, checked against itself and the bytes present.
struct SizeHeader
{
  std::uint64_t bytes = 0;           // decompressed size
  std::vector<std::uint64_t> blocks; // compressed block sizes (compressed files)
  std::uint64_t blockSize = 0;
  std::uint64_t lastBlockSize = 0; // 0: the last block is full
  std::uint64_t compressed = 0;    // sum of blocks
  Stream data;                     // compressed: the blocks; else header and data together
};

// The decompressed size of block @p i of @p count.
std::uint64_t BlockBytes(const SizeHeader& h, std::size_t i, std::size_t count)
{
  return i + 1 == count && h.lastBlockSize != 0 ? h.lastBlockSize : h.blockSize;
}

// Uncompressed: one word, the byte count, then the bytes, in one stream.
SizeHeader ReadPlainHeader(const File& f, const Array& a, const Stream& s)
{
  SizeHeader h;
  std::vector<unsigned char> word;
  if (Read(f, s, f.headerSize, &word) < f.headerSize)
  {
    f.Fail(a.label + ": truncated: the data end (or stop being " + (s.base64 ? "base64" : "bytes") +
      ") inside the size header");
  }
  h.bytes = Word(word, 0, f.headerSize, f.bigEndian);
  h.data = s;
  const std::uint64_t need = AddSat(f.headerSize, h.bytes);
  const std::uint64_t got = need > Capacity(s) ? Capacity(s) : Read(f, s, need, nullptr);
  if (got < need)
  {
    f.Fail(a.label + ": truncated: the size header promises " + std::to_string(h.bytes) + " bytes but only " +
      std::to_string(got > f.headerSize ? got - f.headerSize : 0) + " follow" +
      (s.base64 ? " (the base64 text ends or holds a character that is not base64)" : ""));
  }
  return h;
}

// Compressed: number of blocks, block size, size of the last block (0: full), then each block's
// compressed size; the blocks follow (in base64, as a second stream after the header's padding).
SizeHeader ReadCompressedHeader(const File& f, const Array& a, const Stream& s)
{
  SizeHeader h;
  const std::uint64_t hs = f.headerSize;
  std::vector<unsigned char> words;
  if (Read(f, s, 3 * hs, &words) < 3 * hs)
  {
    f.Fail(a.label + ": truncated: the data end (or stop being base64) inside the compression header");
  }
  const std::uint64_t count = Word(words, 0, hs, f.bigEndian);
  h.blockSize = Word(words, 1, hs, f.bigEndian);
  h.lastBlockSize = Word(words, 2, hs, f.bigEndian);
  if (count > (Capacity(s) - 3 * hs) / hs)
  {
    f.Fail(a.label + ": the compression header lists " + std::to_string(count) +
      " blocks, more than the rest of the file has room for");
  }
  const std::uint64_t headerBytes = hs * (3 + count);
  words.clear();
  if (Read(f, s, headerBytes, &words) < headerBytes)
  {
    f.Fail(a.label + ": truncated: the data end (or stop being base64) inside the list of " + std::to_string(count) +
      " compressed block sizes");
  }
  if (count == 0 && h.lastBlockSize != 0)
  {
    f.Fail(a.label + ": the compression header has no blocks but a last block of " + std::to_string(h.lastBlockSize) +
      " bytes");
  }
  if (count > 0 && h.blockSize == 0)
  {
    f.Fail(a.label + ": the compression header has a block size of 0");
  }
  if (h.lastBlockSize > h.blockSize)
  {
    f.Fail(a.label + ": the compression header's last block (" + std::to_string(h.lastBlockSize) +
      " bytes) is larger than its block size (" + std::to_string(h.blockSize) + ")");
  }
  const std::uint64_t ratio = MaxRatio(f.compressor);
  for (std::size_t i = 0; i < count; ++i)
  {
    h.blocks.push_back(Word(words, 3 + i, hs, f.bigEndian));
    const std::uint64_t size = BlockBytes(h, i, count);
    if (size > MulSat(h.blocks.back(), ratio))
    {
      f.Fail(a.label + ": compressed block " + std::to_string(i) + " of " + std::to_string(h.blocks.back()) +
        " bytes cannot hold " + std::to_string(size) + " bytes (" + CompressorName(f.compressor) +
        " compresses at most " + std::to_string(ratio) + ":1)");
    }
    h.compressed = AddSat(h.compressed, h.blocks.back());
    h.bytes = AddSat(h.bytes, size);
  }
  h.data = s;
  h.data.begin = s.begin + static_cast<std::size_t>(s.base64 ? 4 * ((headerBytes + 2) / 3) : headerBytes);
  const std::uint64_t got = h.compressed > Capacity(h.data) ? Capacity(h.data) : Read(f, h.data, h.compressed, nullptr);
  if (got < h.compressed)
  {
    f.Fail(a.label + ": truncated: the compressed blocks add up to " + std::to_string(h.compressed) +
      " bytes but only " + std::to_string(got) + " follow" +
      (s.base64 ? " (the base64 text ends or holds a character that is not base64)" : ""));
  }
  return h;
}

// Counts @p bytes more towards the budget: arrays may share their appended data, so each one
// fitting is not enough, all of them together must.
void Spend(File& f, const Array& a, std::uint64_t bytes)
{
  f.used = AddSat(f.used, bytes);
  if (f.used > f.budget)
  {
    f.Fail(a.label + ": the arrays up to this one hold " + std::to_string(f.used) + " bytes, more than a " +
      std::to_string(f.data.size()) + "-byte file can hold (" + CompressorName(f.compressor) + ")");
  }
}

// Checks the data of @p a: the size header, the bytes present, and the value count when known
// (@p expected). Returns the size header (empty for ASCII data).
SizeHeader CheckData(File& f, const Array& a, const Expected* expected)
{
  const bool strings = a.type->kind == 's'; // variable length: at least one byte (its end) per string
  if (a.ascii)
  {
    const std::uint64_t present = AsciiValues(f, a, [](const std::string&) { return true; });
    if (expected && present < expected->values)
    {
      f.Fail(a.label + ": " + std::to_string(present) + " ASCII values, expected " + (strings ? "at least " : "") +
        std::to_string(expected->values) + " (" + expected->why + ")");
    }
    Spend(f, a, MulSat(expected ? expected->values : present, a.type->size));
    return SizeHeader();
  }
  const Stream s = Locate(f, a);
  const SizeHeader h = f.compressor == Compressor::None ? ReadPlainHeader(f, a, s) : ReadCompressedHeader(f, a, s);
  const std::uint64_t need = expected ? MulSat(expected->values, a.type->size) : 0;
  if (expected && (strings ? h.bytes < need : h.bytes != need))
  {
    f.Fail(a.label + ": its size header says " + std::to_string(h.bytes) + " bytes, expected " +
      (strings ? "at least " : "") + std::to_string(need) + " (" + expected->why + " x " +
      std::to_string(a.type->size) + "-byte " + a.type->name + ")");
  }
  Spend(f, a, h.bytes);
  return h;
}

vtkSmartPointer<vtkDataCompressor> NewCompressor(Compressor c)
{
  switch (c)
  {
    case Compressor::ZLib:
      return vtkSmartPointer<vtkZLibDataCompressor>::New();
    case Compressor::LZ4:
      return vtkSmartPointer<vtkLZ4DataCompressor>::New();
    case Compressor::LZMA:
      return vtkSmartPointer<vtkLZMADataCompressor>::New();
    case Compressor::None:
      break;
  }
  return nullptr;
}

// The decompressed bytes of a checked binary array (the cell arrays, whose values are checked).
std::vector<unsigned char> Decode(const File& f, const Array& a, const SizeHeader& h)
{
  std::vector<unsigned char> out;
  if (f.compressor == Compressor::None)
  {
    Read(f, h.data, f.headerSize + h.bytes, &out);
    out.erase(out.begin(), out.begin() + static_cast<std::ptrdiff_t>(f.headerSize));
    return out;
  }
  std::vector<unsigned char> packed;
  Read(f, h.data, h.compressed, &packed);
  out.resize(h.bytes);
  const vtkSmartPointer<vtkDataCompressor> compressor = NewCompressor(f.compressor);
  std::size_t in = 0;
  std::size_t at = 0;
  for (std::size_t i = 0; i < h.blocks.size(); ++i)
  {
    const std::size_t size = BlockBytes(h, i, h.blocks.size());
    if (compressor->Uncompress(packed.data() + in, h.blocks[i], out.data() + at, size) != size)
    {
      f.Fail(a.label + ": compressed block " + std::to_string(i) + " is corrupt (it does not decompress to its " +
        std::to_string(size) + " bytes)");
    }
    in += h.blocks[i];
    at += size;
  }
  return out;
}

long long IntegerAt(const unsigned char* p, const ArrayType& t, bool bigEndian)
{
  std::uint64_t bits = 0;
  for (std::uint64_t b = 0; b < t.size; ++b)
  {
    bits |= static_cast<std::uint64_t>(p[bigEndian ? t.size - 1 - b : b]) << (8 * b);
  }
  if (t.kind == 'i' && t.size < 8 && (bits >> (8 * t.size - 1)) != 0)
  {
    return static_cast<long long>(bits) - (1LL << (8 * t.size));
  }
  if (t.kind == 'u' && bits > static_cast<std::uint64_t>(std::numeric_limits<long long>::max()))
  {
    return std::numeric_limits<long long>::max(); // fails every range check below
  }
  long long value = 0;
  std::memcpy(&value, &bits, sizeof value);
  return value;
}

// The values of an integer array with one component (offsets, connectivity, types, faces), which
// must number exactly @p expected.
std::vector<long long> Integers(File& f, const Array& a, const Expected& expected)
{
  if (a.type->kind != 'i' && a.type->kind != 'u')
  {
    f.Fail(a.label + ": must be an integer array, not " + a.type->name);
  }
  if (a.components != 1)
  {
    f.Fail(a.label + ": must have one component");
  }
  const SizeHeader h = CheckData(f, a, &expected);
  std::vector<long long> values;
  if (a.ascii && expected.values > 0)
  {
    AsciiValues(f, a, [&](const std::string& w) {
      long long v = 0;
      ParseSigned(w, v);
      values.push_back(v);
      return values.size() < expected.values;
    });
  }
  if (a.ascii)
  {
    return values;
  }
  const std::vector<unsigned char> bytes = Decode(f, a, h);
  values.reserve(expected.values);
  for (std::size_t i = 0; i < expected.values; ++i)
  {
    values.push_back(IntegerAt(bytes.data() + i * a.type->size, *a.type, f.bigEndian));
  }
  return values;
}

// The first <DataArray> named @p name, the one VTK reads for cells.
const Element* FindNamedArray(const File& f, const Element& parent, const char* name)
{
  for (const std::size_t c : parent.children)
  {
    const std::string* n = f.At(c).Find("Name");
    if (f.At(c).name == "DataArray" && n && *n == name)
    {
      return &f.At(c);
    }
  }
  return nullptr;
}

// ---------------------------------------------------------------------------------------------
// Pieces

std::uint64_t Count(const File& f, const Element& e, const char* name, bool required, const std::string& where)
{
  const std::string* text = e.Find(name);
  if (!text)
  {
    if (required)
    {
      f.Fail(where + ": no " + name + " attribute");
    }
    return 0;
  }
  std::uint64_t n = 0;
  if (!ParseUnsigned(*text, n))
  {
    f.Fail(where + ": " + name + "=\"" + *text + "\" is not a non-negative integer");
  }
  if (n > f.budget)
  {
    f.Fail(where + ": " + name + "=\"" + *text + "\" is more than a " + std::to_string(f.data.size()) +
      "-byte file can hold");
  }
  return n;
}

using Extent = std::array<long long, 6>;

Extent ReadExtent(const File& f, const Element& e, const char* name, const std::string& where)
{
  const std::string* text = e.Find(name);
  if (!text)
  {
    f.Fail(where + ": no " + name + " attribute");
  }
  const std::vector<std::string> words = Split(*text, false);
  Extent ext{};
  constexpr long long limit = 1LL << 30;
  bool ok = words.size() == 6;
  for (std::size_t i = 0; ok && i < 6; ++i)
  {
    ok = ParseSigned(words[i], ext[i]) && ext[i] >= -limit && ext[i] <= limit;
  }
  for (std::size_t i = 0; ok && i < 6; i += 2)
  {
    ok = ext[i] <= ext[i + 1] + 1;
  }
  if (!ok)
  {
    f.Fail(where + ": " + name + "=\"" + *text + "\" is not six integers min max min max min max (|v| <= 2^30)");
  }
  return ext;
}

std::uint64_t ExtentPoints(const Extent& e)
{
  std::uint64_t n = 1;
  for (std::size_t i = 0; i < 6; i += 2)
  {
    n = MulSat(n, static_cast<std::uint64_t>(e[i + 1] - e[i] + 1));
  }
  return n;
}

// VTK's count: no cells when an axis is empty, else the product of max(points - 1, 1).
std::uint64_t ExtentCells(const Extent& e)
{
  std::uint64_t n = 1;
  for (std::size_t i = 0; i < 6; i += 2)
  {
    const std::uint64_t d = static_cast<std::uint64_t>(e[i + 1] - e[i] + 1);
    n = d == 0 ? 0 : MulSat(n, std::max<std::uint64_t>(d - 1, 1));
  }
  return n;
}

// The arrays of a piece's <PointData> or <CellData> (every child is an array to VTK), each with
// @p tuples tuples. VTK creates the output's arrays from the first piece, one per name, and reads
// every piece's elements into them (older versions by position, past the last array when a name
// repeated or a piece had more arrays): names must be distinct and every piece must have the
// first one's layout, which is returned. No VTK writer produces anything else.
struct Layout
{
  std::string signature;
  std::uint64_t bytesPerTuple = 0;
};

Layout CheckAttributeData(
  File& f, const Element& piece, const char* name, std::uint64_t tuples, const std::string& where)
{
  Layout layout;
  const Element* data = OnlyChild(f, piece, name, where);
  if (!data)
  {
    return layout;
  }
  std::vector<std::string> names;
  for (const std::size_t c : data->children)
  {
    const Array a = Describe(f, f.At(c), where + " <" + name + "> array");
    if (const std::string* arrayName = f.At(c).Find("Name"))
    {
      if (std::find(names.begin(), names.end(), *arrayName) != names.end())
      {
        f.Fail(a.label + ": a second array of that name in the same <" + name + ">");
      }
      names.push_back(*arrayName);
    }
    const Expected expected{ MulSat(tuples, a.components),
      std::string(name == std::string("PointData") ? "NumberOfPoints " : "cells ") + std::to_string(tuples) + " x " +
        std::to_string(a.components) + " components" };
    CheckData(f, a, &expected);
    const std::string* arrayName = f.At(c).Find("Name");
    layout.signature += (arrayName ? *arrayName : std::string()) + "|" + a.type->name + "|" +
      std::to_string(a.components) + ";";
    layout.bytesPerTuple = AddSat(layout.bytesPerTuple, MulSat(a.components, a.type->size));
  }
  return layout;
}

// The <Points> of a point set's piece: one array of NumberOfPoints x 3 numbers.
std::string CheckPoints(File& f, const Element& piece, std::uint64_t points, const std::string& where)
{
  const Element* e = OnlyChild(f, piece, "Points", where);
  if (!e)
  {
    if (points > 0)
    {
      f.Fail(where + ": NumberOfPoints=" + std::to_string(points) + " but no <Points>");
    }
    return std::string();
  }
  if (e->children.size() != 1)
  {
    f.Fail(where + ": <Points> must hold exactly one <DataArray>");
  }
  const Array a = Describe(f, f.At(e->children[0]), where + " <Points> array");
  if (a.type->kind == 's' || a.components != 3)
  {
    f.Fail(a.label + ": points must be numbers with 3 components");
  }
  const Expected expected{ MulSat(points, 3), "NumberOfPoints " + std::to_string(points) + " x 3" };
  CheckData(f, a, &expected);
  return a.type->name;
}

// The cells of a polydata <Verts>/<Lines>/<Strips>/<Polys> or an unstructured grid's <Cells>:
// VTK reads @p cells offsets (the end of each cell in the connectivity, increasing), then as many
// connectivity entries as the last offset says; every entry indexes a point of the piece.
void CheckConnectivity(
  File& f, const Element& e, std::uint64_t cells, std::uint64_t points, const std::string& where)
{
  const Element* offsetsElement = FindNamedArray(f, e, "offsets");
  const Element* connectivityElement = FindNamedArray(f, e, "connectivity");
  if (!offsetsElement || !connectivityElement)
  {
    f.Fail(where + ": no '" + (offsetsElement ? "connectivity" : "offsets") + "' array for its " +
      std::to_string(cells) + " cells");
  }
  const Array offsetsArray = Describe(f, *offsetsElement, where + " array");
  const std::vector<long long> offsets =
    Integers(f, offsetsArray, Expected{ cells, "one per cell, " + std::to_string(cells) + " cells" });
  long long last = 0;
  for (std::size_t i = 0; i < offsets.size(); ++i)
  {
    if (offsets[i] < last)
    {
      f.Fail(offsetsArray.label + ": offset " + std::to_string(offsets[i]) + " of cell " + std::to_string(i) +
        " is below the previous one (or negative)");
    }
    last = offsets[i];
  }
  const Array connectivity = Describe(f, *connectivityElement, where + " array");
  const std::vector<long long> ids = Integers(
    f, connectivity, Expected{ static_cast<std::uint64_t>(last), "the last offset, " + std::to_string(last) });
  for (std::size_t i = 0; i < ids.size(); ++i)
  {
    if (ids[i] < 0 || static_cast<std::uint64_t>(ids[i]) >= points)
    {
      f.Fail(connectivity.label + ": entry " + std::to_string(i) + " is point " + std::to_string(ids[i]) +
        ", outside [0, " + std::to_string(points) + ")");
    }
  }
}

// An unstructured grid's cell types, and the faces of its polyhedra: 'faceoffsets' holds, for
// each cell, -1 or the end of its faces in 'faces', where a polyhedron is its number of faces,
// then for each face its number of points and their indices. VTK walks that stream unchecked.
void CheckCellTypesAndFaces(
  File& f, const Element& e, std::uint64_t cells, std::uint64_t points, const std::string& where)
{
  const Element* typesElement = FindNamedArray(f, e, "types");
  if (!typesElement)
  {
    f.Fail(where + ": no 'types' array for its " + std::to_string(cells) + " cells");
  }
  const Array typesArray = Describe(f, *typesElement, where + " array");
  const std::vector<long long> types =
    Integers(f, typesArray, Expected{ cells, "one per cell, NumberOfCells " + std::to_string(cells) });
  bool polyhedra = false;
  for (std::size_t i = 0; i < types.size(); ++i)
  {
    if (types[i] < 0 || types[i] >= VTK_NUMBER_OF_CELL_TYPES ||
      std::strcmp(vtkCellTypes::GetClassNameFromTypeId(static_cast<int>(types[i])), "UnknownClass") == 0)
    {
      f.Fail(typesArray.label + ": cell " + std::to_string(i) + " has the unknown type " + std::to_string(types[i]));
    }
    polyhedra = polyhedra || types[i] == VTK_POLYHEDRON;
  }
  const Element* facesElement = FindNamedArray(f, e, "faces");
  const Element* faceOffsetsElement = FindNamedArray(f, e, "faceoffsets");
  if (!facesElement || !faceOffsetsElement)
  {
    if (polyhedra || facesElement || faceOffsetsElement)
    {
      f.Fail(where + ": polyhedron cells need both a 'faces' and a 'faceoffsets' array");
    }
    return;
  }
  const Array faceOffsetsArray = Describe(f, *faceOffsetsElement, where + " array");
  const std::vector<long long> faceOffsets =
    Integers(f, faceOffsetsArray, Expected{ cells, "one per cell, NumberOfCells " + std::to_string(cells) });
  long long length = -1;
  for (const long long o : faceOffsets)
  {
    length = o >= 0 ? o : length;
  }
  if (length <= 0)
  {
    if (polyhedra)
    {
      f.Fail(faceOffsetsArray.label + ": the grid has polyhedra but no faces");
    }
    return; // VTK does not read 'faces' then
  }
  const Array facesArray = Describe(f, *facesElement, where + " array");
  const std::vector<long long> faces =
    Integers(f, facesArray, Expected{ static_cast<std::uint64_t>(length), "the last face offset" });
  std::size_t at = 0;
  auto next = [&](std::size_t cell) {
    if (at >= faces.size())
    {
      f.Fail(facesArray.label + ": the faces of cell " + std::to_string(cell) + " run past its end");
    }
    return faces[at++];
  };
  for (std::size_t i = 0; i < faceOffsets.size(); ++i)
  {
    if ((faceOffsets[i] >= 0) != (types[i] == VTK_POLYHEDRON) || faceOffsets[i] < -1)
    {
      f.Fail(faceOffsetsArray.label + ": cell " + std::to_string(i) + " has face offset " +
        std::to_string(faceOffsets[i]) +
        (types[i] == VTK_POLYHEDRON ? " but is a polyhedron" : " but is not a polyhedron"));
    }
    if (faceOffsets[i] < 0)
    {
      continue;
    }
    auto count = [&]() {
      const long long n = next(i);
      if (n < 0)
      {
        f.Fail(facesArray.label + ": cell " + std::to_string(i) + " has a negative face or point count");
      }
      return n;
    };
    const long long faceCount = count();
    for (long long k = 0; k < faceCount; ++k)
    {
      const long long n = count();
      for (long long j = 0; j < n; ++j)
      {
        const long long id = next(i);
        if (id < 0 || static_cast<std::uint64_t>(id) >= points)
        {
          f.Fail(facesArray.label + ": a face of cell " + std::to_string(i) + " uses point " + std::to_string(id) +
            ", outside [0, " + std::to_string(points) + ")");
        }
      }
    }
    if (static_cast<long long>(at) != faceOffsets[i])
    {
      f.Fail(facesArray.label + ": the faces of cell " + std::to_string(i) + " end at " + std::to_string(at) +
        ", 'faceoffsets' says " + std::to_string(faceOffsets[i]));
    }
  }
}

// The <FieldData> of the dataset element: each array holds NumberOfTuples tuples (when given).
void CheckFieldData(File& f, const Element& primary)
{
  for (const Element* data : Children(f, primary, "FieldData"))
  {
    for (const std::size_t c : data->children)
    {
      const Array a = Describe(f, f.At(c), "<FieldData> array");
      const bool counted = f.At(c).Find("NumberOfTuples") != nullptr;
      const std::uint64_t tuples = Count(f, f.At(c), "NumberOfTuples", false, a.label);
      const Expected expected{ MulSat(tuples, a.components), "NumberOfTuples " + std::to_string(tuples) + " x " +
          std::to_string(a.components) + " components" };
      CheckData(f, a, counted ? &expected : nullptr);
    }
  }
}

// One piece of a .vtp or .vtu; returns its layout signature.
std::string CheckPointSetPiece(File& f, const Element& piece, bool grid, const std::string& where)
{
  const std::uint64_t points = Count(f, piece, "NumberOfPoints", true, where);
  std::uint64_t cells = 0;
  std::string signature = CheckPoints(f, piece, points, where) + "/";
  if (grid)
  {
    cells = Count(f, piece, "NumberOfCells", true, where);
    const Element* e = OnlyChild(f, piece, "Cells", where);
    if (cells > 0 && !e)
    {
      f.Fail(where + ": NumberOfCells=" + std::to_string(cells) + " but no <Cells>");
    }
    if (cells > 0)
    {
      CheckConnectivity(f, *e, cells, points, where + " <Cells>");
      CheckCellTypesAndFaces(f, *e, cells, points, where + " <Cells>");
    }
  }
  else
  {
    static const char* const kinds[] = { "Verts", "Lines", "Strips", "Polys" };
    for (const char* kind : kinds)
    {
      const std::uint64_t n = Count(f, piece, (std::string("NumberOf") + kind).c_str(), false, where);
      const Element* e = OnlyChild(f, piece, kind, where);
      if (n > 0 && !e)
      {
        f.Fail(where + ": NumberOf" + kind + "=" + std::to_string(n) + " but no <" + kind + ">");
      }
      if (n > 0)
      {
        CheckConnectivity(f, *e, n, points, where + " <" + kind + ">");
      }
      cells = AddSat(cells, n);
    }
  }
  signature += CheckAttributeData(f, piece, "PointData", points, where).signature + "/";
  return signature + CheckAttributeData(f, piece, "CellData", cells, where).signature;
}

void CheckPointSet(File& f, const Element& primary, bool grid)
{
  std::string first;
  std::size_t index = 0;
  for (const Element* piece : Children(f, primary, "Piece"))
  {
    const std::string where = "piece " + std::to_string(index);
    const std::string signature = CheckPointSetPiece(f, *piece, grid, where);
    if (index > 0 && signature != first)
    {
      f.Fail(where + ": its arrays differ from piece 0's (VTK sizes every array by the first piece)");
    }
    first = index == 0 ? signature : first;
    ++index;
  }
}

void CheckImage(File& f, const Element& primary)
{
  const Extent whole = ReadExtent(f, primary, "WholeExtent", "<ImageData>");
  const std::uint64_t pointLimit = std::max(f.budget, SmallImage);
  if (ExtentPoints(whole) > pointLimit)
  {
    f.Fail("<ImageData>: WholeExtent has " + std::to_string(ExtentPoints(whole)) + " points, more than a " +
      std::to_string(f.data.size()) + "-byte file can describe");
  }
  Layout first;
  std::size_t index = 0;
  for (const Element* piece : Children(f, primary, "Piece"))
  {
    const std::string where = "piece " + std::to_string(index);
    const Extent ext = ReadExtent(f, *piece, "Extent", where);
    for (std::size_t i = 0; i < 6; i += 2)
    {
      if (ExtentPoints(ext) > 0 && (ext[i] < whole[i] || ext[i + 1] > whole[i + 1]))
      {
        f.Fail(where + ": its Extent is not inside the WholeExtent");
      }
    }
    const Layout pointData = CheckAttributeData(f, *piece, "PointData", ExtentPoints(ext), where);
    const Layout cellData = CheckAttributeData(f, *piece, "CellData", ExtentCells(ext), where);
    const std::string signature = pointData.signature + "/" + cellData.signature;
    if (index > 0 && signature != first.signature)
    {
      f.Fail(where + ": its arrays differ from piece 0's (VTK sizes every array by the first piece)");
    }
    if (index == 0)
    {
      first.signature = signature;
      // The output's arrays cover the whole extent.
      if (AddSat(MulSat(ExtentPoints(whole), pointData.bytesPerTuple),
            MulSat(ExtentCells(whole), cellData.bytesPerTuple)) > f.budget)
      {
        f.Fail("<ImageData>: arrays over the WholeExtent would need more bytes than a " +
          std::to_string(f.data.size()) + "-byte file can hold");
      }
    }
    ++index;
  }
}

// The root element: the dataset type of the extension, the byte order, header size and compressor
// that every binary array is read with.
void CheckRoot(File& f, const std::string& type)
{
  const Element& root = f.At(0);
  if (root.name != "VTKFile")
  {
    f.Fail("the root element is <" + root.name + ">, not <VTKFile>");
  }
  const std::string* t = root.Find("type");
  if (!t || *t != type)
  {
    f.Fail("<VTKFile type=\"" + (t ? *t : std::string()) + "\">, expected \"" + type + "\" for a " +
      Extension(f.path) + " file");
  }
  if (const std::string* v = root.Find("version"))
  {
    const std::size_t dot = v->find('.');
    std::uint64_t major = 0;
    std::uint64_t minor = 0;
    if (dot == std::string::npos || !ParseUnsigned(v->substr(0, dot), major) ||
      !ParseUnsigned(v->substr(dot + 1), minor))
    {
      f.Fail("<VTKFile version=\"" + *v + "\">: expected MAJOR.MINOR");
    }
  }
  if (const std::string* order = root.Find("byte_order"))
  {
    if (*order != "LittleEndian" && *order != "BigEndian")
    {
      f.Fail("<VTKFile byte_order=\"" + *order + "\">: expected LittleEndian or BigEndian");
    }
    f.bigEndian = *order == "BigEndian";
  }
  if (const std::string* header = root.Find("header_type"))
  {
    if (*header != "UInt32" && *header != "UInt64")
    {
      f.Fail("<VTKFile header_type=\"" + *header + "\">: expected UInt32 or UInt64");
    }
    f.headerSize = *header == "UInt64" ? 8 : 4;
  }
  if (const std::string* c = root.Find("compressor"))
  {
    const Compressor known[] = { Compressor::ZLib, Compressor::LZ4, Compressor::LZMA };
    const auto it =
      std::find_if(std::begin(known), std::end(known), [&](Compressor k) { return *c == CompressorName(k); });
    if (it == std::end(known))
    {
      f.Fail("<VTKFile compressor=\"" + *c +
        "\">: unknown compressor (VTK knows vtkZLibDataCompressor, vtkLZ4DataCompressor and vtkLZMADataCompressor)");
    }
    f.compressor = *it;
  }
  // ASCII values take at least two characters each and become at most 8 bytes: the budget is
  // never below 8 bytes per byte of file.
  f.budget = MulSat(std::max<std::uint64_t>(f.data.size(), 1), std::max<std::uint64_t>(MaxRatio(f.compressor), 8));
}

void Validate(const std::string& path)
{
  File f;
  f.path = path;
  {
    std::ifstream in(path, std::ios::binary);
    f.data.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  const std::string ext = Extension(path);
  const std::string type = ext == ".vtp" ? "PolyData" : ext == ".vtu" ? "UnstructuredGrid" : "ImageData";
  f.doc = ParseMarkup(f);
  CheckRoot(f, type);
  const std::vector<const Element*> primaries = Children(f, f.At(0), type.c_str());
  if (primaries.empty())
  {
    f.Fail("no <" + type + "> element in <VTKFile>");
  }
  const Element& primary = *primaries[0]; // the one VTK reads
  if (primary.Find("TimeValues"))
  {
    f.Fail("<" + type + ">: files with TimeValues are not supported");
  }
  CheckFieldData(f, primary);
  if (type == "ImageData")
  {
    CheckImage(f, primary);
  }
  else
  {
    CheckPointSet(f, primary, type == "UnstructuredGrid");
  }
}

} // namespace vtkxml

template <class ReaderT>
vtkSmartPointer<vtkDataSet> ReadXML(const std::string& path)
{
  vtkNew<ReaderT> reader;
  if (!reader->CanReadFile(path.c_str()))
  {
    throw std::runtime_error("cannot read " + path + " (missing, or not a " + Extension(path) + " file)");
  }
  vtkxml::Validate(path);
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkSmartPointer<vtkDataSet> out = vtkDataSet::SafeDownCast(reader->GetOutputDataObject(0));
  if (!out)
  {
    throw std::runtime_error("failed to read " + path);
  }
  return out;
}

template <class WriterT>
void WriteXML(vtkDataObject* data, const std::string& path, Compression compression)
{
  vtkNew<WriterT> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(data);
  // Appended raw binary: inline binary data is base64 text, a third larger and about as slow
  // to encode as the compression itself.
  writer->SetDataModeToAppended();
  writer->EncodeAppendedDataOff();
  switch (compression)
  {
    case Compression::LZ4:
      writer->SetCompressorTypeToLZ4();
      break;
    case Compression::ZLib:
      writer->SetCompressorTypeToZLib();
      break;
    case Compression::None:
      writer->SetCompressorTypeToNone();
      break;
  }
  if (writer->Write() == 0)
  {
    throw std::runtime_error("cannot write " + path);
  }
}

} // namespace

std::string Extension(const std::string& path)
{
  const auto slash = path.find_last_of("/\\");
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
  {
    return "";
  }
  return Lower(path.substr(dot));
}

vtkSmartPointer<vtkDataSet> ReadDataSet(const std::string& path)
{
  {
    std::ifstream probe(path);
    if (!probe)
    {
      throw std::runtime_error("cannot open " + path);
    }
  }
  const std::string ext = Extension(path);
  if (ext == ".vtp")
    return ReadXML<vtkXMLPolyDataReader>(path);
  if (ext == ".vtu")
    return ReadXML<vtkXMLUnstructuredGridReader>(path);
  if (ext == ".vti")
    return ReadXML<vtkXMLImageDataReader>(path);
  if (ext == ".csv")
    return ReadTable(path, true);
  if (ext == ".xyz" || ext == ".txt")
    return ReadTable(path, false);
  if (ext == ".ply")
  {
    vtkNew<vtkPLYReader> reader;
    if (!reader->CanReadFile(path.c_str()))
    {
      throw std::runtime_error("cannot read " + path + " as PLY");
    }
    ply::Validate(path);
    reader->SetFileName(path.c_str());
    reader->Update();
    vtkSmartPointer<vtkDataSet> out = reader->GetOutput();
    if (out->GetNumberOfPoints() == 0)
    {
      throw std::runtime_error(path + " has no points");
    }
    return out;
  }
  throw std::runtime_error("unknown input format '" + ext + "' of " + path + " (use .vtp .vtu .vti .ply .csv .xyz)");
}

namespace
{

// VTK's PLY writer keeps only float normals (nx, ny, nz); ours are double.
vtkSmartPointer<vtkPolyData> WithFloatNormals(vtkPolyData* mesh)
{
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(mesh);
  vtkDataArray* normals = mesh->GetPointData()->GetNormals();
  if (normals && normals->GetDataType() != VTK_FLOAT)
  {
    vtkNew<vtkFloatArray> single;
    single->DeepCopy(normals);
    single->SetName(normals->GetName());
    out->GetPointData()->SetNormals(single);
  }
  return out;
}

// STL and OBJ hold geometry only (OBJ also the normals): for meshes, through VTK's own writers.
void WriteMeshOnly(vtkPolyData* mesh, const std::string& path, const std::string& ext)
{
  if (mesh->GetNumberOfPolys() == 0 && ext == ".stl")
  {
    throw std::runtime_error("cannot write " + path + ": STL holds triangles, and this output has none");
  }
  vtkSmartPointer<vtkWriter> writer;
  if (ext == ".stl")
  {
    auto stl = vtkSmartPointer<vtkSTLWriter>::New();
    stl->SetFileTypeToBinary();
    stl->SetFileName(path.c_str());
    writer = stl;
  }
  else
  {
    auto obj = vtkSmartPointer<vtkOBJWriter>::New();
    obj->SetFileName(path.c_str());
    writer = obj;
  }
  writer->SetInputData(mesh);
  if (writer->Write() == 0)
  {
    throw std::runtime_error("cannot write " + path);
  }
}

} // namespace

void WriteDataSet(vtkDataSet* data, const std::string& path, Compression compression)
{
  const std::string ext = Extension(path);
  if (ext == ".vtp")
  {
    WriteXML<vtkXMLPolyDataWriter>(AsPolyData(data), path, compression);
  }
  else if (ext == ".vtu")
  {
    vtkNew<vtkAppendFilter> toGrid;
    toGrid->AddInputData(data);
    toGrid->Update();
    WriteXML<vtkXMLUnstructuredGridWriter>(toGrid->GetOutput(), path, compression);
  }
  else if (ext == ".vti")
  {
    auto* image = vtkImageData::SafeDownCast(data);
    if (!image)
    {
      throw std::runtime_error("only image data (pss sample on a grid) can be written as .vti");
    }
    WriteXML<vtkXMLImageDataWriter>(image, path, compression);
  }
  else if (ext == ".ply")
  {
    vtkNew<vtkPLYWriter> writer;
    writer->SetFileName(path.c_str());
    writer->SetInputData(WithFloatNormals(AsPolyData(data)));
    writer->SetFileTypeToBinary();
    if (writer->Write() == 0)
    {
      throw std::runtime_error("cannot write " + path);
    }
  }
  else if (ext == ".stl" || ext == ".obj")
  {
    WriteMeshOnly(AsPolyData(data), path, ext);
  }
  else if (ext == ".csv")
  {
    WriteTable(data, path, true);
  }
  else if (ext == ".xyz" || ext == ".txt")
  {
    WriteTable(data, path, false);
  }
  else
  {
    throw std::runtime_error(
      "unknown output format '" + ext + "' of " + path + " (use .vtp .vtu .vti .ply .stl .obj .csv .xyz)");
  }
}

}
