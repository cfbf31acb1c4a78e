// SPDX-License-Identifier: BSD-3-Clause
#include "Mesh.h"

#include "vtkOBJWriter.h"
#include "vtkPolyData.h"
#include "vtkSTLWriter.h"
#include "vtkSmartPointer.h"
#include "vtkWriter.h"

#include <stdexcept>

namespace pss_cli
{
namespace io
{

void WriteMesh(vtkPolyData* mesh, const std::string& path, const std::string& ext)
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

}
}
