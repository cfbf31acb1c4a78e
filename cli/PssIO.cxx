// SPDX-License-Identifier: BSD-3-Clause
#include "PssIO.h"

#include "vtkAppendFilter.h"
#include "vtkCellArray.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkIdTypeArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPLYWriter.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkUnstructuredGrid.h"
#include "vtkXMLImageDataReader.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLPolyDataReader.h"
#include "vtkXMLPolyDataWriter.h"
#include "vtkXMLUnstructuredGridReader.h"
#include "vtkXMLUnstructuredGridWriter.h"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <fstream>
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
      const int nc = array->GetNumberOfComponents();
      for (int c = 0; c < nc; ++c)
      {
        out << ',' << array->GetName();
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

template <class ReaderT>
vtkSmartPointer<vtkDataSet> ReadXML(const std::string& path)
{
  vtkNew<ReaderT> reader;
  if (!reader->CanReadFile(path.c_str()))
  {
    throw std::runtime_error("cannot read " + path + " (missing, or not a " + Extension(path) + " file)");
  }
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
  writer->SetDataModeToBinary();
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
    writer->SetInputData(AsPolyData(data));
    writer->SetFileTypeToBinary();
    if (writer->Write() == 0)
    {
      throw std::runtime_error("cannot write " + path);
    }
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
    throw std::runtime_error("unknown output format '" + ext + "' of " + path + " (use .vtp .vtu .vti .ply .csv .xyz)");
  }
}

}
