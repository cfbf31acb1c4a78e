// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPCDReader.h"

#include "PointSetSurfacesPCD.h"
#include "PointSetSurfacesVertexCells.h"

#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkPCDReader);

namespace
{

using pss_pcd::Field;

// The VTK type that holds a field's elements bit for bit.
int VtkType(const Field& field)
{
  if (field.type == 'F')
  {
    return field.size == 4 ? VTK_FLOAT : VTK_DOUBLE;
  }
  const bool u = field.type == 'U';
  switch (field.size)
  {
    case 1: return u ? VTK_UNSIGNED_CHAR : VTK_SIGNED_CHAR;
    case 2: return u ? VTK_UNSIGNED_SHORT : VTK_SHORT;
    case 4: return u ? VTK_UNSIGNED_INT : VTK_INT;
    default: return u ? VTK_TYPE_UINT64 : VTK_TYPE_INT64;
  }
}

// One element of @p field at @p p, as a double (for the points of integer or mixed-type files).
double Element(const Field& field, const unsigned char* p)
{
  const auto load = [p](auto value) {
    std::memcpy(&value, p, sizeof value);
    return static_cast<double>(value);
  };
  if (field.type == 'F')
  {
    return field.size == 4 ? load(float()) : load(double());
  }
  const bool u = field.type == 'U';
  switch (field.size)
  {
    case 1: return u ? load(std::uint8_t()) : load(std::int8_t());
    case 2: return u ? load(std::uint16_t()) : load(std::int16_t());
    case 4: return u ? load(std::uint32_t()) : load(std::int32_t());
    default: return u ? load(std::uint64_t()) : load(std::int64_t());
  }
}

// The decoded file with the rows the output keeps (all of them when `all`).
struct Source
{
  const pss_pcd::Cloud& cloud;
  std::vector<std::size_t> rows;
  bool all = true;

  std::size_t size() const { return this->all ? static_cast<std::size_t>(this->cloud.header.points) : this->rows.size(); }
  std::size_t row(std::size_t j) const { return this->all ? j : this->rows[j]; }
  const unsigned char* column(std::size_t f) const
  {
    // An empty body has no memory to point into (and no offset to add to it).
    if (this->cloud.columns.bytes.empty())
    {
      return nullptr;
    }
    return this->cloud.columns.bytes.data() + this->cloud.columns.start[f];
  }
};

// Calls @p body(begin, end) over [0, n) in parallel chunks (vtkSMPTools): the copies of a large
// cloud are bound by memory and first-touch page faults, which two threads take apart.
template <typename Body>
void ForRange(std::size_t n, Body&& body)
{
  vtkSMPTools::For(0, static_cast<vtkIdType>(n), 1 << 16, [&body](vtkIdType begin, vtkIdType end) {
    body(static_cast<std::size_t>(begin), static_cast<std::size_t>(end));
  });
}

// Copies, for every kept row j, @p Size bytes from in + row(j) * inStride to out + j * outStride; a
// memcpy of a constant size is a single move, so each element size gets its own loop.
template <std::size_t Size>
void GatherFixed(const Source& source, const unsigned char* in, std::size_t inStride, unsigned char* out,
  std::size_t outStride)
{
  ForRange(source.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t j = begin; j < end; ++j)
    {
      std::memcpy(out + j * outStride, in + source.row(j) * inStride, Size);
    }
  });
}

void Gather(const Source& source, std::size_t size, const unsigned char* in, std::size_t inStride, unsigned char* out,
  std::size_t outStride)
{
  if (source.size() == 0)
  {
    return;
  }
  switch (size)
  {
    case 1: GatherFixed<1>(source, in, inStride, out, outStride); return;
    case 2: GatherFixed<2>(source, in, inStride, out, outStride); return;
    case 4: GatherFixed<4>(source, in, inStride, out, outStride); return;
    case 8: GatherFixed<8>(source, in, inStride, out, outStride); return;
    default:
      ForRange(source.size(), [&](std::size_t begin, std::size_t end) {
        for (std::size_t j = begin; j < end; ++j)
        {
          std::memcpy(out + j * outStride, in + source.row(j) * inStride, size);
        }
      });
  }
}

// A point array holding field @p f's kept rows, bit for bit.
vtkSmartPointer<vtkDataArray> FieldArray(const Source& source, std::size_t f)
{
  const Field& field = source.cloud.header.fields[f];
  auto array = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(VtkType(field)));
  array->SetName(field.name.c_str());
  array->SetNumberOfComponents(static_cast<int>(field.count));
  array->SetNumberOfTuples(static_cast<vtkIdType>(source.size()));
  auto* out = static_cast<unsigned char*>(array->GetVoidPointer(0));
  const std::size_t width = field.bytesPerPoint();
  const unsigned char* in = source.column(f);
  if (source.all)
  {
    ForRange(source.size(), [&](std::size_t begin, std::size_t end) {
      std::memcpy(out + begin * width, in + begin * width, (end - begin) * width);
    });
    return array;
  }
  Gather(source, width, in, width, out, width);
  return array;
}

// `RGB` or `RGBA` from a 4-byte rgb / rgba field (0xAARRGGBB).
vtkSmartPointer<vtkDataArray> ColorArray(const Source& source, std::size_t f, bool alpha)
{
  auto colors = vtkSmartPointer<vtkUnsignedCharArray>::New();
  colors->SetName(alpha ? "RGBA" : "RGB");
  const int components = alpha ? 4 : 3;
  colors->SetNumberOfComponents(components);
  colors->SetNumberOfTuples(static_cast<vtkIdType>(source.size()));
  unsigned char* out = colors->GetPointer(0);
  const unsigned char* in = source.column(f);
  for (std::size_t j = 0; j < source.size(); ++j)
  {
    std::uint32_t bits = 0;
    std::memcpy(&bits, in + source.row(j) * 4, 4);
    unsigned char* c = out + j * components;
    c[0] = static_cast<unsigned char>(bits >> 16);
    c[1] = static_cast<unsigned char>(bits >> 8);
    c[2] = static_cast<unsigned char>(bits);
    if (alpha)
    {
      c[3] = static_cast<unsigned char>(bits >> 24);
    }
  }
  return colors;
}

// Interleaves three single-component fields of one type into a 3-component array.
vtkSmartPointer<vtkDataArray> TripleArray(const Source& source, const std::size_t f[3], const char* name)
{
  const Field& field = source.cloud.header.fields[f[0]];
  auto array = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(VtkType(field)));
  array->SetName(name);
  array->SetNumberOfComponents(3);
  array->SetNumberOfTuples(static_cast<vtkIdType>(source.size()));
  auto* out = static_cast<unsigned char*>(array->GetVoidPointer(0));
  const std::size_t size = field.size;
  for (int c = 0; source.size() > 0 && c < 3; ++c)
  {
    Gather(source, size, source.column(f[c]), size, out + c * size, 3 * size);
  }
  return array;
}

// Index of the single-element field @p name, or -1.
long FindField(const pss_pcd::Header& header, const char* name)
{
  for (std::size_t f = 0; f < header.fields.size(); ++f)
  {
    if (header.fields[f].name == name && header.fields[f].count == 1)
    {
      return static_cast<long>(f);
    }
  }
  return -1;
}

// Three single-element fields of one type, or false.
bool FindTriple(const pss_pcd::Header& header, const char* const names[3], std::size_t f[3])
{
  for (int c = 0; c < 3; ++c)
  {
    const long index = FindField(header, names[c]);
    if (index < 0)
    {
      return false;
    }
    f[c] = static_cast<std::size_t>(index);
    const Field& field = header.fields[f[c]];
    if (field.type != header.fields[f[0]].type || field.size != header.fields[f[0]].size)
    {
      return false;
    }
  }
  return true;
}

vtkSmartPointer<vtkPoints> MakePoints(const Source& source, const std::size_t xyz[3])
{
  const auto& fields = source.cloud.header.fields;
  const Field& x = fields[xyz[0]];
  const bool sameFloats = x.type == 'F' && fields[xyz[1]].type == 'F' && fields[xyz[2]].type == 'F' &&
    fields[xyz[1]].size == x.size && fields[xyz[2]].size == x.size;
  auto points = vtkSmartPointer<vtkPoints>::New();
  if (sameFloats)
  {
    // Float or double coordinates are kept bit for bit.
    points->SetData(TripleArray(source, xyz, "Points"));
    return points;
  }
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(static_cast<vtkIdType>(source.size()));
  double* out = static_cast<vtkDoubleArray*>(points->GetData())->GetPointer(0);
  for (int c = 0; c < 3; ++c)
  {
    const Field& field = fields[xyz[c]];
    const unsigned char* in = source.column(xyz[c]);
    for (std::size_t j = 0; j < source.size(); ++j)
    {
      out[3 * j + c] = Element(field, in + source.row(j) * field.size);
    }
  }
  return points;
}

// Clears finite[i] where element i of a coordinate column is NaN or infinite (integers never are).
template <typename T>
void MarkNonFiniteTyped(const unsigned char* column, std::vector<unsigned char>& finite)
{
  ForRange(finite.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i)
    {
      T value;
      std::memcpy(&value, column + i * sizeof(T), sizeof(T));
      finite[i] &= static_cast<unsigned char>(std::isfinite(value));
    }
  });
}

void MarkNonFinite(const Field& field, const unsigned char* column, std::vector<unsigned char>& finite)
{
  if (field.type == 'F')
  {
    field.size == 4 ? MarkNonFiniteTyped<float>(column, finite) : MarkNonFiniteTyped<double>(column, finite);
  }
}

template <typename ArrayT, typename T>
void AddFieldData(vtkPolyData* output, const char* name, std::initializer_list<T> values)
{
  vtkNew<ArrayT> array;
  array->SetName(name);
  for (T v : values)
  {
    array->InsertNextValue(v);
  }
  output->GetFieldData()->AddArray(array);
}

} // namespace

vtkPCDReader::vtkPCDReader()
{
  this->SetNumberOfInputPorts(0);
}

vtkPCDReader::~vtkPCDReader()
{
  this->SetFileName(nullptr);
}

bool vtkPCDReader::CanReadFile(const char* fileName)
{
  std::ifstream in(fileName ? fileName : "", std::ios::binary);
  std::string line;
  for (int i = 0; i < 16 && std::getline(in, line); ++i)
  {
    if (line.empty() || line[0] == '#')
    {
      continue;
    }
    return line.rfind("VERSION", 0) == 0 || line.rfind("FIELDS", 0) == 0 || line.rfind("COLUMNS", 0) == 0;
  }
  return false;
}

int vtkPCDReader::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  this->NumberOfSkippedPoints = 0;
  this->NumberOfPointsInFile = 0;
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro(<< "no FileName was set");
    return 0;
  }
  pss_pcd::Cloud cloud;
  try
  {
    cloud = pss_pcd::ReadFile(this->FileName);
  }
  catch (const std::exception& error)
  {
    vtkErrorMacro(<< error.what());
    return 0;
  }
  this->UpdateProgress(0.5);
  const pss_pcd::Header& header = cloud.header;
  if (header.points > static_cast<std::uint64_t>(VTK_ID_MAX / 2))
  {
    vtkErrorMacro(<< this->FileName << ": " << header.points << " points are more than VTK can index");
    return 0;
  }
  if (header.organized() && (header.width > VTK_INT_MAX || header.height > VTK_INT_MAX))
  {
    vtkErrorMacro(<< this->FileName << ": an organized cloud of " << header.width << " x " << header.height
                  << " pixels is beyond 2^31 - 1 along a side");
    return 0;
  }
  this->NumberOfPointsInFile = static_cast<vtkIdType>(header.points);

  // Mixed types are fine for the points (they become doubles); a missing coordinate is not.
  static const char* const xyzNames[3] = { "x", "y", "z" };
  std::size_t xyz[3];
  for (int c = 0; c < 3; ++c)
  {
    const long index = FindField(header, xyzNames[c]);
    if (index < 0)
    {
      vtkErrorMacro(<< this->FileName << ": the file has no single-element field '" << xyzNames[c] << "'");
      return 0;
    }
    xyz[c] = static_cast<std::size_t>(index);
  }

  Source source{ cloud, {}, true };
  if (this->SkipNaNPoints && header.points > 0)
  {
    const std::size_t n = static_cast<std::size_t>(header.points);
    std::vector<unsigned char> finite(n, 1);
    for (int c = 0; c < 3; ++c)
    {
      MarkNonFinite(header.fields[xyz[c]], source.column(xyz[c]), finite);
    }
    const std::size_t kept = static_cast<std::size_t>(std::count(finite.begin(), finite.end(), 1));
    if (kept < n)
    {
      source.rows.reserve(kept);
      for (std::size_t i = 0; i < n; ++i)
      {
        if (finite[i])
        {
          source.rows.push_back(i);
        }
      }
      source.all = false;
      this->NumberOfSkippedPoints = static_cast<vtkIdType>(n - kept);
    }
  }

  const vtkIdType kept = static_cast<vtkIdType>(source.size());
  output->SetPoints(MakePoints(source, xyz));
  if (this->GenerateVertices)
  {
    output->SetVerts(pss_vtk::VertexCells(kept));
  }
  vtkPointData* pointData = output->GetPointData();

  // Arrays in the order of the fields, so that a file written from the output has the same order.
  static const char* const normalNames[3] = { "normal_x", "normal_y", "normal_z" };
  std::size_t normals[3];
  const bool hasNormals = FindTriple(header, normalNames, normals) && header.fields[normals[0]].type == 'F';
  for (std::size_t f = 0; f < header.fields.size(); ++f)
  {
    const Field& field = header.fields[f];
    if (hasNormals && f == normals[0])
    {
      pointData->SetNormals(TripleArray(source, normals, "Normals"));
      continue;
    }
    const bool isNormal = hasNormals && (f == normals[1] || f == normals[2]);
    if (field.name == "_" || f == xyz[0] || f == xyz[1] || f == xyz[2] || isNormal)
    {
      continue;
    }
    if ((field.name == "rgb" || field.name == "rgba") && field.size == 4 && field.count == 1)
    {
      pointData->SetScalars(ColorArray(source, f, field.name == "rgba"));
      continue;
    }
    if (pointData->HasArray(field.name.c_str()))
    {
      vtkWarningMacro(<< this->FileName << ": the field '" << field.name << "' is left out: an array of that name exists");
      continue;
    }
    pointData->AddArray(FieldArray(source, f));
  }
  if (header.organized())
  {
    vtkNew<vtkIntArray> pixels;
    pixels->SetName("Pixel");
    pixels->SetNumberOfComponents(2);
    pixels->SetNumberOfTuples(kept);
    for (vtkIdType j = 0; j < kept; ++j)
    {
      const std::size_t i = source.row(static_cast<std::size_t>(j));
      pixels->SetTypedComponent(j, 0, static_cast<int>(i % header.width));
      pixels->SetTypedComponent(j, 1, static_cast<int>(i / header.width));
    }
    pointData->AddArray(pixels);
  }

  AddFieldData<vtkIdTypeArray, vtkIdType>(
    output, "GridDimensions", { static_cast<vtkIdType>(header.width), static_cast<vtkIdType>(header.height) });
  if (header.hasViewpoint)
  {
    const auto& v = header.viewpoint;
    AddFieldData<vtkDoubleArray, double>(output, "Viewpoint", { v[0], v[1], v[2], v[3], v[4], v[5], v[6] });
  }
  AddFieldData<vtkIdTypeArray, vtkIdType>(output, "SkippedPoints", { this->NumberOfSkippedPoints });
  this->UpdateProgress(1.0);
  return 1;
}

void vtkPCDReader::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "SkipNaNPoints: " << (this->SkipNaNPoints ? "On" : "Off") << "\n";
  os << indent << "GenerateVertices: " << (this->GenerateVertices ? "On" : "Off") << "\n";
  os << indent << "NumberOfSkippedPoints: " << this->NumberOfSkippedPoints << "\n";
  os << indent << "NumberOfPointsInFile: " << this->NumberOfPointsInFile << "\n";
}
