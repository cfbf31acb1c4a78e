// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPCDWriter.h"

#include "PointSetSurfacesPCD.h"

#include "vtkDataArray.h"
#include "vtkErrorCode.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"

#include <cstring>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkPCDWriter);

namespace
{

using pss_pcd::Field;

// The k-th value of @p array counted over tuples and components (field data of 7 values may be
// one tuple of 7 or 7 tuples of 1).
double Value(vtkDataArray* array, int k)
{
  const int components = array->GetNumberOfComponents();
  return array->GetComponent(k / components, k % components);
}

// Where each input point goes among the file's rows: itself, or its pixel of an organized image.
struct Layout
{
  std::size_t rows = 0;
  std::size_t width = 0, height = 1;
  std::vector<std::size_t> rowOf; ///< empty: point j is row j
  std::size_t row(std::size_t j) const { return this->rowOf.empty() ? j : this->rowOf[j]; }
};

// The organized image that GridDimensions and Pixel describe, when they describe one.
Layout MakeLayout(vtkPointSet* input)
{
  const std::size_t n = static_cast<std::size_t>(input->GetNumberOfPoints());
  Layout layout;
  layout.rows = layout.width = n;
  vtkDataArray* grid = input->GetFieldData()->GetArray("GridDimensions");
  vtkDataArray* pixel = input->GetPointData()->GetArray("Pixel");
  if (!grid || grid->GetNumberOfValues() != 2 || !pixel || pixel->GetNumberOfComponents() != 2 ||
    static_cast<std::size_t>(pixel->GetNumberOfTuples()) != n)
  {
    return layout;
  }
  const double w = Value(grid, 0), h = Value(grid, 1);
  if (!(h > 1 && w >= 1 && w * h <= 4e9 && w * h >= static_cast<double>(n)))
  {
    return layout;
  }
  Layout organized;
  organized.width = static_cast<std::size_t>(w);
  organized.height = static_cast<std::size_t>(h);
  organized.rows = organized.width * organized.height;
  organized.rowOf.resize(n);
  std::vector<bool> taken(organized.rows, false);
  for (std::size_t j = 0; j < n; ++j)
  {
    const double col = pixel->GetComponent(static_cast<vtkIdType>(j), 0);
    const double row = pixel->GetComponent(static_cast<vtkIdType>(j), 1);
    if (!(col >= 0 && col < w && row >= 0 && row < h) || col != static_cast<std::size_t>(col) ||
      row != static_cast<std::size_t>(row))
    {
      return layout;
    }
    const std::size_t r = static_cast<std::size_t>(row) * organized.width + static_cast<std::size_t>(col);
    if (taken[r])
    {
      return layout;
    }
    taken[r] = true;
    organized.rowOf[j] = r;
  }
  return organized;
}

// A PCD TYPE and SIZE for a VTK type, or false when PCD has none.
bool PcdType(int vtkType, Field& field)
{
  switch (vtkType)
  {
    case VTK_FLOAT: field.type = 'F'; field.size = 4; return true;
    case VTK_DOUBLE: field.type = 'F'; field.size = 8; return true;
    case VTK_CHAR:
    case VTK_SIGNED_CHAR: field.type = 'I'; field.size = 1; return true;
    case VTK_UNSIGNED_CHAR: field.type = 'U'; field.size = 1; return true;
    case VTK_SHORT: field.type = 'I'; field.size = 2; return true;
    case VTK_UNSIGNED_SHORT: field.type = 'U'; field.size = 2; return true;
    case VTK_INT: field.type = 'I'; field.size = 4; return true;
    case VTK_UNSIGNED_INT: field.type = 'U'; field.size = 4; return true;
    case VTK_LONG:
    case VTK_LONG_LONG:
    case VTK_ID_TYPE: field.type = 'I'; field.size = 8; return sizeof(long) == 8 || vtkType != VTK_LONG;
    case VTK_UNSIGNED_LONG:
    case VTK_UNSIGNED_LONG_LONG: field.type = 'U'; field.size = 8; return sizeof(long) == 8 || vtkType != VTK_UNSIGNED_LONG;
    default: return false;
  }
}

// One column to write: its field and, per input point, the bytes of its row.
struct Column
{
  Field field;
  vtkDataArray* array = nullptr;
  enum Kind
  {
    Copy,        ///< the array's tuple, bit for bit
    Component,   ///< one component of the array (of the field's type)
    ToDouble,    ///< one component converted to double
    PackedColor  ///< RGB(A) unsigned chars packed into 0xAARRGGBB
  } kind = Copy;
  int component = 0;
};

void FillColumn(const Column& column, const Layout& layout, std::size_t n, unsigned char* out)
{
  const std::size_t width = column.field.bytesPerPoint();
  if (layout.rows > n)
  {
    // Pixels without a point: NaN in floating-point fields (as PCL marks invalid pixels), else 0.
    if (column.field.type == 'F')
    {
      const float nanFloat = std::numeric_limits<float>::quiet_NaN();
      const double nanDouble = std::numeric_limits<double>::quiet_NaN();
      for (std::size_t k = 0; k < layout.rows * column.field.count; ++k)
      {
        column.field.size == 4 ? std::memcpy(out + 4 * k, &nanFloat, 4) : std::memcpy(out + 8 * k, &nanDouble, 8);
      }
    }
    else
    {
      std::memset(out, 0, layout.rows * width);
    }
  }
  if (n == 0)
  {
    return; // an image with no point at all: every pixel filled above
  }
  vtkDataArray* array = column.array;
  const auto* data = static_cast<const unsigned char*>(array->GetVoidPointer(0));
  const std::size_t size = column.field.size;
  const std::size_t components = static_cast<std::size_t>(array->GetNumberOfComponents());
  for (std::size_t j = 0; j < n; ++j)
  {
    unsigned char* dst = out + layout.row(j) * width;
    switch (column.kind)
    {
      case Column::Copy: std::memcpy(dst, data + j * width, width); break;
      case Column::Component:
        std::memcpy(dst, data + (j * components + static_cast<std::size_t>(column.component)) * size, size);
        break;
      case Column::ToDouble:
      {
        const double value = array->GetComponent(static_cast<vtkIdType>(j), column.component);
        std::memcpy(dst, &value, 8);
        break;
      }
      case Column::PackedColor:
      {
        const unsigned char* c = data + j * components;
        const std::uint32_t bits = static_cast<std::uint32_t>(c[0]) << 16 | static_cast<std::uint32_t>(c[1]) << 8 |
          c[2] | (components == 4 ? static_cast<std::uint32_t>(c[3]) << 24 : 0u);
        std::memcpy(dst, &bits, 4);
        break;
      }
    }
  }
}

std::string FieldName(const char* name, int index)
{
  std::string out = name && *name ? name : "array_" + std::to_string(index);
  for (char& c : out)
  {
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r')
    {
      c = '_';
    }
  }
  return out;
}

} // namespace

vtkPCDWriter::vtkPCDWriter() = default;

vtkPCDWriter::~vtkPCDWriter()
{
  this->SetFileName(nullptr);
}

int vtkPCDWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

void vtkPCDWriter::WriteData()
{
  auto* input = vtkPointSet::SafeDownCast(this->GetInput());
  if (!input)
  {
    vtkErrorMacro(<< "the input is not a point set");
    return;
  }
  if (!this->FileName || !*this->FileName)
  {
    vtkErrorMacro(<< "no FileName was set");
    this->SetErrorCode(vtkErrorCode::NoFileNameError);
    return;
  }
  const std::size_t n = static_cast<std::size_t>(input->GetNumberOfPoints());
  const Layout layout = MakeLayout(input);

  std::vector<Column> columns;
  const auto add = [&columns](const std::string& name, vtkDataArray* array, Column::Kind kind, int component,
                     const Field& typed, std::size_t count) {
    Column column;
    column.field = typed;
    column.field.name = name;
    column.field.count = count;
    column.array = array;
    column.kind = kind;
    column.component = component;
    columns.push_back(column);
  };
  Field typed;
  if (n > 0)
  {
    vtkDataArray* points = input->GetPoints()->GetData();
    const bool asFloat = points->GetDataType() == VTK_FLOAT && points->HasStandardMemoryLayout();
    PcdType(asFloat ? VTK_FLOAT : VTK_DOUBLE, typed);
    for (int c = 0; c < 3; ++c)
    {
      add(std::string(1, "xyz"[c]), points, asFloat ? Column::Component : Column::ToDouble, c, typed, 1);
    }
  }
  else
  {
    PcdType(VTK_FLOAT, typed);
    for (int c = 0; c < 3; ++c)
    {
      add(std::string(1, "xyz"[c]), nullptr, Column::Copy, c, typed, 1);
    }
  }
  vtkPointData* pointData = input->GetPointData();
  for (int a = 0; a < pointData->GetNumberOfArrays(); ++a)
  {
    vtkAbstractArray* abstract = pointData->GetAbstractArray(a);
    vtkDataArray* array = vtkDataArray::SafeDownCast(abstract);
    const std::string name = FieldName(abstract->GetName(), a);
    const int components = abstract->GetNumberOfComponents();
    if (name == "Pixel" && !layout.rowOf.empty())
    {
      continue; // the row of each point in the image says it
    }
    if (!array || !array->HasStandardMemoryLayout() || !PcdType(array->GetDataType(), typed) || components < 1)
    {
      vtkWarningMacro(<< "the point array '" << name << "' is left out: PCD holds numeric arrays only");
      continue;
    }
    bool taken = name == "x" || name == "y" || name == "z";
    for (const Column& column : columns)
    {
      taken = taken || column.field.name == name;
    }
    // Only the active colours and normals take PCD's own fields: what vtkPCDReader makes of them.
    if (array == pointData->GetScalars() && (name == "RGB" || name == "RGBA") &&
      array->GetDataType() == VTK_UNSIGNED_CHAR && components == (name == "RGB" ? 3 : 4))
    {
      PcdType(VTK_UNSIGNED_INT, typed);
      add(name == "RGB" ? "rgb" : "rgba", array, Column::PackedColor, 0, typed, 1);
    }
    else if (array == pointData->GetNormals() && components == 3 && typed.type == 'F')
    {
      for (int c = 0; c < 3; ++c)
      {
        add(std::string("normal_") + "xyz"[c], array, Column::Component, c, typed, 1);
      }
    }
    else if (taken)
    {
      vtkWarningMacro(<< "the point array '" << name << "' is left out: a field of that name is written already");
    }
    else
    {
      add(name, array, Column::Copy, 0, typed, static_cast<std::size_t>(components));
    }
  }

  pss_pcd::Cloud cloud;
  pss_pcd::Header& header = cloud.header;
  header.data = this->DataMode == ASCII ? pss_pcd::DataKind::Ascii
    : this->DataMode == BINARY          ? pss_pcd::DataKind::Binary
                                        : pss_pcd::DataKind::BinaryCompressed;
  header.width = layout.width;
  header.height = layout.height;
  header.points = layout.rows;
  header.hasViewpoint = true;
  if (vtkDataArray* viewpoint = input->GetFieldData()->GetArray("Viewpoint"))
  {
    if (viewpoint->GetNumberOfValues() == 7)
    {
      for (int k = 0; k < 7; ++k)
      {
        header.viewpoint[static_cast<std::size_t>(k)] = Value(viewpoint, k);
      }
    }
  }
  for (const Column& column : columns)
  {
    header.fields.push_back(column.field);
  }
  cloud.columns.start = pss_pcd::ColumnStarts(header);
  const std::size_t offset = layout.rows * header.pointSize();
  try
  {
    cloud.columns.bytes.resize(offset);
    for (std::size_t f = 0; f < columns.size() && offset > 0; ++f)
    {
      FillColumn(columns[f], layout, n, cloud.columns.bytes.data() + cloud.columns.start[f]);
    }
    const std::vector<unsigned char> bytes = pss_pcd::Encode(cloud);
    std::ofstream out(this->FileName, std::ios::binary | std::ios::trunc);
    if (!out)
    {
      this->SetErrorCode(vtkErrorCode::CannotOpenFileError);
      throw std::runtime_error(std::string("cannot open ") + this->FileName + " for writing");
    }
    out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
    if (!out.flush())
    {
      this->SetErrorCode(vtkErrorCode::OutOfDiskSpaceError);
      throw std::runtime_error(std::string("cannot write ") + this->FileName);
    }
  }
  catch (const std::exception& error)
  {
    if (this->GetErrorCode() == vtkErrorCode::NoError)
    {
      this->SetErrorCode(vtkErrorCode::UnknownError);
    }
    vtkErrorMacro(<< error.what());
  }
}

void vtkPCDWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << (this->FileName ? this->FileName : "(none)") << "\n";
  os << indent << "DataMode: " << this->DataMode << "\n";
}
