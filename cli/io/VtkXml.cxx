// SPDX-License-Identifier: BSD-3-Clause
#include "VtkXml.h"

#include "Text.h"
#include "VtkXmlFile.h"

#include "vtkCellType.h"
#include "vtkCellTypes.h"
#include "vtkDataSet.h"
#include "vtkNew.h"
#include "vtkXMLDataElement.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"
#include "vtkXMLUnstructuredGridReader.h"
#include "vtkXMLUnstructuredGridWriter.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>

namespace pss_cli
{
namespace io
{

namespace
{

// VTK XML files are checked here, before VTK's readers see them. Those readers trust the file:
// the counts of a Piece (NumberOfPoints, NumberOfCells, Extent), the size header in front of
// every binary array (block count, block sizes, compressed sizes) and the cell offsets size
// their allocations and index their buffers, so one corrupted number makes them allocate
// gigabytes, divide by zero or read outside a buffer (found by tests/fuzz/FuzzCliInput.cxx).
// What passes is consistent: every count fits in what the file can hold, every size header
// agrees with the counts and with the bytes actually present, every cell index stays inside its
// arrays. Everything else fails with the element or array that is wrong. The markup is parsed by
// vtkXMLDataParser, as the readers parse it (VtkXmlFile.h).
using namespace vtkxml;

// An image's points are implicit (its Extent): an image of up to 2^20 points is accepted whatever
// its file size; beyond, the file must hold data for them.
constexpr std::uint64_t SmallImage = std::uint64_t(1) << 20;

using Extent = std::array<long long, 6>;

Extent ReadExtent(const File& f, vtkXMLDataElement* e, const char* name, const std::string& where)
{
  const std::optional<std::string> text = Attribute(e, name);
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
  File& f, vtkXMLDataElement* piece, const char* name, std::uint64_t tuples, const std::string& where)
{
  Layout layout;
  vtkXMLDataElement* data = OnlyChild(f, piece, name, where);
  if (!data)
  {
    return layout;
  }
  std::vector<std::string> names;
  for (vtkXMLDataElement* child : Children(data))
  {
    const Array a = Describe(f, child, where + " <" + name + "> array");
    const std::optional<std::string> arrayName = Attribute(child, "Name");
    if (arrayName)
    {
      if (std::find(names.begin(), names.end(), *arrayName) != names.end())
      {
        f.Fail(a.label + ": a second array of that name in the same <" + name + ">");
      }
      names.push_back(*arrayName);
    }
    const Expected expected{ MulSat(tuples, a.components),
      std::string(std::strcmp(name, "PointData") == 0 ? "NumberOfPoints " : "cells ") + std::to_string(tuples) +
        " x " + std::to_string(a.components) + " components" };
    CheckData(f, a, &expected);
    layout.signature += arrayName.value_or("") + "|" + a.type->name + "|" + std::to_string(a.components) + ";";
    layout.bytesPerTuple = AddSat(layout.bytesPerTuple, MulSat(a.components, a.type->size));
  }
  return layout;
}

// The <Points> of a point set's piece: one array of NumberOfPoints x 3 numbers.
std::string CheckPoints(File& f, vtkXMLDataElement* piece, std::uint64_t points, const std::string& where)
{
  vtkXMLDataElement* e = OnlyChild(f, piece, "Points", where);
  if (!e)
  {
    if (points > 0)
    {
      f.Fail(where + ": NumberOfPoints=" + std::to_string(points) + " but no <Points>");
    }
    return std::string();
  }
  if (e->GetNumberOfNestedElements() != 1)
  {
    f.Fail(where + ": <Points> must hold exactly one <DataArray>");
  }
  const Array a = Describe(f, e->GetNestedElement(0), where + " <Points> array");
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
  File& f, vtkXMLDataElement* e, std::uint64_t cells, std::uint64_t points, const std::string& where)
{
  vtkXMLDataElement* offsetsElement = FindNamedArray(e, "offsets");
  vtkXMLDataElement* connectivityElement = FindNamedArray(e, "connectivity");
  if (!offsetsElement || !connectivityElement)
  {
    f.Fail(where + ": no '" + (offsetsElement ? "connectivity" : "offsets") + "' array for its " +
      std::to_string(cells) + " cells");
  }
  // Streamed: a large cloud's vertex cells are checked without a copy of them.
  const Array offsetsArray = Describe(f, offsetsElement, where + " array");
  long long last = 0;
  std::uint64_t cell = 0;
  ForEachInteger(f, offsetsArray, Expected{ cells, "one per cell, " + std::to_string(cells) + " cells" },
    [&](const long long* offsets, std::size_t n) {
      for (std::size_t i = 0; i < n; ++i, ++cell)
      {
        if (offsets[i] < last)
        {
          f.Fail(offsetsArray.label + ": offset " + std::to_string(offsets[i]) + " of cell " + std::to_string(cell) +
            " is below the previous one (or negative)");
        }
        last = offsets[i];
      }
    });
  const Array connectivity = Describe(f, connectivityElement, where + " array");
  std::uint64_t entry = 0;
  ForEachInteger(f, connectivity,
    Expected{ static_cast<std::uint64_t>(last), "the last offset, " + std::to_string(last) }, [&](const long long* ids, std::size_t n) {
      for (std::size_t i = 0; i < n; ++i, ++entry)
      {
        if (ids[i] < 0 || static_cast<std::uint64_t>(ids[i]) >= points)
        {
          f.Fail(connectivity.label + ": entry " + std::to_string(entry) + " is point " + std::to_string(ids[i]) +
            ", outside [0, " + std::to_string(points) + ")");
        }
      }
    });
}

// An unstructured grid's cell types, and the faces of its polyhedra: 'faceoffsets' holds, for
// each cell, -1 or the end of its faces in 'faces', where a polyhedron is its number of faces,
// then for each face its number of points and their indices. VTK walks that stream unchecked.
void CheckCellTypesAndFaces(
  File& f, vtkXMLDataElement* e, std::uint64_t cells, std::uint64_t points, const std::string& where)
{
  vtkXMLDataElement* typesElement = FindNamedArray(e, "types");
  if (!typesElement)
  {
    f.Fail(where + ": no 'types' array for its " + std::to_string(cells) + " cells");
  }
  const Array typesArray = Describe(f, typesElement, where + " array");
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
  vtkXMLDataElement* facesElement = FindNamedArray(e, "faces");
  vtkXMLDataElement* faceOffsetsElement = FindNamedArray(e, "faceoffsets");
  if (!facesElement || !faceOffsetsElement)
  {
    if (polyhedra || facesElement || faceOffsetsElement)
    {
      f.Fail(where + ": polyhedron cells need both a 'faces' and a 'faceoffsets' array");
    }
    return;
  }
  const Array faceOffsetsArray = Describe(f, faceOffsetsElement, where + " array");
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
  const Array facesArray = Describe(f, facesElement, where + " array");
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
void CheckFieldData(File& f, vtkXMLDataElement* primary)
{
  for (vtkXMLDataElement* data : Children(primary, "FieldData"))
  {
    for (vtkXMLDataElement* child : Children(data))
    {
      const Array a = Describe(f, child, "<FieldData> array");
      const bool counted = Attribute(child, "NumberOfTuples").has_value();
      const std::uint64_t tuples = Count(f, child, "NumberOfTuples", false, a.label);
      const Expected expected{ MulSat(tuples, a.components), "NumberOfTuples " + std::to_string(tuples) + " x " +
          std::to_string(a.components) + " components" };
      CheckData(f, a, counted ? &expected : nullptr);
    }
  }
}

// One piece of a .vtp or .vtu; returns its layout signature.
std::string CheckPointSetPiece(File& f, vtkXMLDataElement* piece, bool grid, const std::string& where)
{
  const std::uint64_t points = Count(f, piece, "NumberOfPoints", true, where);
  std::uint64_t cells = 0;
  std::string signature = CheckPoints(f, piece, points, where) + "/";
  if (grid)
  {
    cells = Count(f, piece, "NumberOfCells", true, where);
    vtkXMLDataElement* e = OnlyChild(f, piece, "Cells", where);
    if (cells > 0 && !e)
    {
      f.Fail(where + ": NumberOfCells=" + std::to_string(cells) + " but no <Cells>");
    }
    if (cells > 0)
    {
      CheckConnectivity(f, e, cells, points, where + " <Cells>");
      CheckCellTypesAndFaces(f, e, cells, points, where + " <Cells>");
    }
  }
  else
  {
    static const char* const kinds[] = { "Verts", "Lines", "Strips", "Polys" };
    for (const char* kind : kinds)
    {
      const std::uint64_t n = Count(f, piece, (std::string("NumberOf") + kind).c_str(), false, where);
      vtkXMLDataElement* e = OnlyChild(f, piece, kind, where);
      if (n > 0 && !e)
      {
        f.Fail(where + ": NumberOf" + kind + "=" + std::to_string(n) + " but no <" + kind + ">");
      }
      if (n > 0)
      {
        CheckConnectivity(f, e, n, points, where + " <" + kind + ">");
      }
      cells = AddSat(cells, n);
    }
  }
  signature += CheckAttributeData(f, piece, "PointData", points, where).signature + "/";
  return signature + CheckAttributeData(f, piece, "CellData", cells, where).signature;
}

void CheckPointSet(File& f, vtkXMLDataElement* primary, bool grid)
{
  std::string first;
  std::size_t index = 0;
  for (vtkXMLDataElement* piece : Children(primary, "Piece"))
  {
    const std::string where = "piece " + std::to_string(index);
    const std::string signature = CheckPointSetPiece(f, piece, grid, where);
    if (index > 0 && signature != first)
    {
      f.Fail(where + ": its arrays differ from piece 0's (VTK sizes every array by the first piece)");
    }
    first = index == 0 ? signature : first;
    ++index;
  }
}

void CheckImage(File& f, vtkXMLDataElement* primary)
{
  const Extent whole = ReadExtent(f, primary, "WholeExtent", "<ImageData>");
  const std::uint64_t pointLimit = std::max(f.budget, SmallImage);
  if (ExtentPoints(whole) > pointLimit)
  {
    f.Fail("<ImageData>: WholeExtent has " + std::to_string(ExtentPoints(whole)) + " points, more than a " +
      std::to_string(f.size) + "-byte file can describe");
  }
  Layout first;
  std::size_t index = 0;
  for (vtkXMLDataElement* piece : Children(primary, "Piece"))
  {
    const std::string where = "piece " + std::to_string(index);
    const Extent ext = ReadExtent(f, piece, "Extent", where);
    for (std::size_t i = 0; i < 6; i += 2)
    {
      if (ExtentPoints(ext) > 0 && (ext[i] < whole[i] || ext[i + 1] > whole[i + 1]))
      {
        f.Fail(where + ": its Extent is not inside the WholeExtent");
      }
    }
    const Layout pointData = CheckAttributeData(f, piece, "PointData", ExtentPoints(ext), where);
    const Layout cellData = CheckAttributeData(f, piece, "CellData", ExtentCells(ext), where);
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
        f.Fail("<ImageData>: arrays over the WholeExtent would need more bytes than a " + std::to_string(f.size) +
          "-byte file can hold");
      }
    }
    ++index;
  }
}

// The root element: the dataset type of the extension, the byte order, header size and compressor
// that every binary array is read with.
void CheckRoot(File& f, const std::string& type)
{
  vtkXMLDataElement* root = f.Root();
  if (std::strcmp(root->GetName(), "VTKFile") != 0)
  {
    f.Fail(std::string("the root element is <") + root->GetName() + ">, not <VTKFile>");
  }
  const std::optional<std::string> t = Attribute(root, "type");
  if (t != type)
  {
    f.Fail("<VTKFile type=\"" + t.value_or("") + "\">, expected \"" + type + "\" for a " + Extension(f.path) +
      " file");
  }
  if (const std::optional<std::string> v = Attribute(root, "version"))
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
  if (const std::optional<std::string> order = Attribute(root, "byte_order"))
  {
    if (*order != "LittleEndian" && *order != "BigEndian")
    {
      f.Fail("<VTKFile byte_order=\"" + *order + "\">: expected LittleEndian or BigEndian");
    }
    f.bigEndian = *order == "BigEndian";
  }
  if (const std::optional<std::string> header = Attribute(root, "header_type"))
  {
    if (*header != "UInt32" && *header != "UInt64")
    {
      f.Fail("<VTKFile header_type=\"" + *header + "\">: expected UInt32 or UInt64");
    }
    f.headerSize = *header == "UInt64" ? 8 : 4;
  }
  if (const std::optional<std::string> c = Attribute(root, "compressor"))
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
  f.budget = MulSat(std::max<std::uint64_t>(f.size, 1), std::max<std::uint64_t>(MaxRatio(f.compressor), 8));
}

void Validate(const std::string& path, const std::string& type)
{
  File f(path);
  CheckRoot(f, type);
  const std::vector<vtkXMLDataElement*> primaries = Children(f.Root(), type.c_str());
  if (primaries.empty())
  {
    f.Fail("no <" + type + "> element in <VTKFile>");
  }
  vtkXMLDataElement* primary = primaries[0]; // the one VTK reads
  if (Attribute(primary, "TimeValues"))
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

template <class ReaderT>
vtkSmartPointer<vtkDataSet> Read(const std::string& path, const std::string& type)
{
  vtkNew<ReaderT> reader;
  if (!reader->CanReadFile(path.c_str()))
  {
    throw std::runtime_error("cannot read " + path + " (missing, or not a " + Extension(path) + " file)");
  }
  Validate(path, type);
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
void Write(vtkDataObject* data, const std::string& path, Compression compression)
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

vtkSmartPointer<vtkDataSet> ReadVtkXml(const std::string& path)
{
  const std::string ext = Extension(path);
  if (ext == ".vtp")
  {
    return Read<vtkXMLPolyDataReader>(path, "PolyData");
  }
  if (ext == ".vtu")
  {
    return Read<vtkXMLUnstructuredGridReader>(path, "UnstructuredGrid");
  }
  return Read<vtkXMLImageDataReader>(path, "ImageData");
}

void WriteVtkXml(vtkDataObject* data, const std::string& path, Compression compression)
{
  const std::string ext = Extension(path);
  if (ext == ".vtp")
  {
    Write<vtkXMLPolyDataWriter>(data, path, compression);
  }
  else if (ext == ".vtu")
  {
    Write<vtkXMLUnstructuredGridWriter>(data, path, compression);
  }
  else
  {
    Write<vtkXMLImageDataWriter>(data, path, compression);
  }
}

}
}
