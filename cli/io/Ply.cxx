// SPDX-License-Identifier: BSD-3-Clause
#include "Ply.h"

#include "Bytes.h"
#include "PointSetSurfacesWords.h"

#include "vtkDataArray.h"
#include "vtkFloatArray.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPLYWriter.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <vector>

namespace pss_cli
{
namespace io
{

namespace
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
  for (const std::string_view word : pss_vtk::SplitWords(line))
  {
    words.emplace_back(word);
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
  const auto size = static_cast<std::size_t>(type.size);
  if (type.kind == 'i')
  {
    return std::max<long long>(LoadSigned(p, size, bigEndian), -1); // -1: negative
  }
  return static_cast<long long>(LoadUnsigned(p, size, bigEndian));
}

// A value of @p type at @p p, as a double (the face indices' range check).
double DecodeValue(const unsigned char* p, const Type& type, bool bigEndian)
{
  const auto size = static_cast<std::size_t>(type.size);
  if (type.kind == 'i')
  {
    return static_cast<double>(LoadSigned(p, size, bigEndian));
  }
  const std::uint64_t bits = LoadUnsigned(p, size, bigEndian);
  if (type.kind == 'f' && size == 4)
  {
    float f = 0.0f;
    const auto u = static_cast<std::uint32_t>(bits);
    std::memcpy(&f, &u, sizeof f);
    return f;
  }
  if (type.kind == 'f')
  {
    double d = 0.0;
    std::memcpy(&d, &bits, sizeof d);
    return d;
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

// The whole file, header and body, before VTK's reader sees it: that reader (the
// Stanford ply library) trusts the file, and a header without end_header, an unknown type, a list
// where it expects a number, a truncated body or a blank line inside an ASCII body make it read
// freed or unallocated memory, or abort on an assert (found by tests/fuzz/FuzzCliInput.cxx).
// What passes is exactly what it reads safely; everything else fails with the line or element
// that is wrong.
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
    // VTK's reader frees an uninitialized property list when it closes a file with such an
    // element, rows or not (a crash the fuzzer found with 'element face 0' and no property).
    if (e.properties.empty())
    {
      throw std::runtime_error(where + "element '" + e.name + "' declares no properties");
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

} // namespace

vtkSmartPointer<vtkDataSet> ReadPly(const std::string& path)
{
  vtkNew<vtkPLYReader> reader;
  if (!reader->CanReadFile(path.c_str()))
  {
    throw std::runtime_error("cannot read " + path + " as PLY");
  }
  Validate(path);
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkSmartPointer<vtkDataSet> out = reader->GetOutput();
  if (out->GetNumberOfPoints() == 0)
  {
    throw std::runtime_error(path + " has no points");
  }
  return out;
}

void WritePly(vtkPolyData* mesh, const std::string& path)
{
  vtkNew<vtkPLYWriter> writer;
  writer->SetFileName(path.c_str());
  writer->SetInputData(WithFloatNormals(mesh));
  writer->SetFileTypeToBinary();
  if (writer->Write() == 0)
  {
    throw std::runtime_error("cannot write " + path);
  }
}

}
}
