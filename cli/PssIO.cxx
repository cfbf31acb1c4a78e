// SPDX-License-Identifier: BSD-3-Clause
// Reading and writing by extension; each format's code is in io/ (Table, Ply, VtkXml, Mesh).
#include "PssIO.h"

#include "io/Mesh.h"
#include "io/Pcd.h"
#include "io/Ply.h"
#include "io/Table.h"
#include "io/Text.h"
#include "io/VtkXml.h"

#include "vtkAppendFilter.h"
#include "vtkCellArray.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPointSet.h"
#include "vtkPolyData.h"
#include "vtkUnstructuredGrid.h"

#include <fstream>
#include <stdexcept>

namespace pss_cli
{

namespace
{

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

} // namespace

std::string Extension(const std::string& path)
{
  const auto slash = path.find_last_of("/\\");
  const auto dot = path.find_last_of('.');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
  {
    return "";
  }
  return io::Lower(path.substr(dot));
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
  if (ext == ".vtp" || ext == ".vtu" || ext == ".vti")
    return io::ReadVtkXml(path);
  if (ext == ".csv")
    return io::ReadTable(path, true);
  if (ext == ".xyz" || ext == ".txt")
    return io::ReadTable(path, false);
  if (ext == ".ply")
    return io::ReadPly(path);
  if (ext == ".pcd")
    return io::ReadPcd(path);
  throw std::runtime_error("unknown input format '" + ext + "' of " + path + " (use .vtp .vtu .vti .ply .pcd .csv .xyz)");
}

void WriteDataSet(vtkDataSet* data, const std::string& path, Compression compression)
{
  const std::string ext = Extension(path);
  if (ext == ".vtp")
  {
    io::WriteVtkXml(AsPolyData(data), path, compression);
  }
  else if (ext == ".vtu")
  {
    vtkNew<vtkAppendFilter> toGrid;
    toGrid->AddInputData(data);
    toGrid->Update();
    io::WriteVtkXml(toGrid->GetOutput(), path, compression);
  }
  else if (ext == ".vti")
  {
    auto* image = vtkImageData::SafeDownCast(data);
    if (!image)
    {
      throw std::runtime_error("only image data (pss sample on a grid) can be written as .vti");
    }
    io::WriteVtkXml(image, path, compression);
  }
  else if (ext == ".ply")
  {
    io::WritePly(AsPolyData(data), path);
  }
  else if (ext == ".pcd")
  {
    auto* pointSet = vtkPointSet::SafeDownCast(data);
    if (!pointSet)
    {
      throw std::runtime_error("only point sets can be written as .pcd; write image data as .vti");
    }
    io::WritePcd(pointSet, path, compression != Compression::None);
  }
  else if (ext == ".stl" || ext == ".obj")
  {
    io::WriteMesh(AsPolyData(data), path, ext);
  }
  else if (ext == ".csv")
  {
    io::WriteTable(data, path, true);
  }
  else if (ext == ".xyz" || ext == ".txt")
  {
    io::WriteTable(data, path, false);
  }
  else
  {
    throw std::runtime_error(
      "unknown output format '" + ext + "' of " + path + " (use .vtp .vtu .vti .ply .pcd .stl .obj .csv .xyz)");
  }
}

}
