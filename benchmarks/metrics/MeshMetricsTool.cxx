// SPDX-License-Identifier: BSD-3-Clause
/**
 * pss-mesh-metrics MESH REFERENCE [CLOUD] [--spurious D] [--threshold T] [--unit U] [--loops H]
 *
 * Prints the comparison of the mesh issue for any triangle mesh (ours, MeshLab's, Poisson's):
 * accuracy (mesh to REFERENCE), completeness (REFERENCE's vertices to the mesh, and the share
 * beyond --threshold), the share of the mesh's area farther than --spurious from every CLOUD point,
 * and its topology. Distances in the files' units; --unit scales the printout (default 1e-6: um
 * for files in metres). --loops H also sorts every boundary loop of the mesh: at one of REFERENCE's
 * own holes (half its vertices within 3 H of REFERENCE's border), at a gap of the scan (no CLOUD
 * point within H of its centre; H = the mesher's MaxDistance, 1 h), or other (ClassifyBoundary),
 * and lists them in mm (for files in metres). Meshes: .vtp .ply .stl .obj.
 *
 * pss-mesh-metrics MESH CLOUD --no-reference [--unit U]
 *
 * Without a reference surface (a real scan): topology, the boundary loops that are small holes
 * (shorter than 40 local point spacings, with CLOUD points within 2 spacings of their centre) and
 * the far area (mesh farther than 3 local spacings from every CLOUD point) and the uncovered points
 * (CLOUD points farther than 2 local spacings from the mesh): MeasureWithoutReference.
 * CLOUD may also be a .pcd file (its NaN pixels are left out).
 */
#include "MeshMetrics.h"

#include "vtkAlgorithm.h"
#include "vtkNew.h"
#include "vtkOBJReader.h"
#include "vtkPCDReader.h"
#include "vtkPLYReader.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSTLReader.h"
#include "vtkSmartPointer.h"
#include "vtkXMLPolyDataReader.h"

#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

namespace
{

const char* const Usage = "usage: pss-mesh-metrics MESH REFERENCE [CLOUD] [--spurious D] [--threshold T] [--unit U] "
                          "[--loops H]\n"
                          "       pss-mesh-metrics MESH CLOUD --no-reference [--unit U]\n";

vtkSmartPointer<vtkPolyData> Read(const std::string& path)
{
  auto endsWith = [&](const char* ext) {
    const std::string e(ext);
    return path.size() >= e.size() && path.compare(path.size() - e.size(), e.size(), e) == 0;
  };
  vtkSmartPointer<vtkAlgorithm> reader;
  if (endsWith(".ply"))
  {
    auto r = vtkSmartPointer<vtkPLYReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (endsWith(".vtp"))
  {
    auto r = vtkSmartPointer<vtkXMLPolyDataReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (endsWith(".stl"))
  {
    auto r = vtkSmartPointer<vtkSTLReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (endsWith(".obj"))
  {
    auto r = vtkSmartPointer<vtkOBJReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else if (endsWith(".pcd"))
  {
    auto r = vtkSmartPointer<vtkPCDReader>::New();
    r->SetFileName(path.c_str());
    reader = r;
  }
  else
  {
    std::cerr << "pss-mesh-metrics: unknown format of " << path << " (use .vtp .ply .stl .obj, or .pcd for a cloud)\n";
    std::exit(1);
  }
  reader->Update();
  auto* out = vtkPolyData::SafeDownCast(reader->GetOutputDataObject(0));
  if (!out || out->GetNumberOfPoints() == 0)
  {
    std::cerr << "pss-mesh-metrics: cannot read " << path << "\n";
    std::exit(1);
  }
  return out;
}

}

int main(int argc, char** argv)
{
  std::vector<std::string> positional;
  pss_metrics::MetricOptions options;
  double unit = 1e-6;
  double loops = 0.0; // > 0: classify the boundary loops, with this gap distance (MaxDistance, 1 h)
  bool noReference = false;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    auto value = [&]() {
      if (i + 1 >= argc)
      {
        std::cerr << "pss-mesh-metrics: " << a << " needs a value\n";
        std::exit(2);
      }
      return std::atof(argv[++i]);
    };
    if (a == "--spurious")
      options.spuriousDistance = value();
    else if (a == "--threshold")
      options.completenessThreshold = value();
    else if (a == "--unit")
      unit = value();
    else if (a == "--loops")
      loops = value();
    else if (a == "--no-reference")
      noReference = true;
    else if (a == "--help" || a == "-h")
    {
      std::cout << Usage;
      return 0;
    }
    else
      positional.push_back(a);
  }
  if (noReference)
  {
    if (positional.size() != 2)
    {
      std::cerr << Usage;
      return 2;
    }
    vtkSMPTools::SetBackend("STDThread");
    vtkSmartPointer<vtkPolyData> mesh = Read(positional[0]);
    vtkSmartPointer<vtkPolyData> cloud = Read(positional[1]);
    const pss_metrics::ReferenceFreeQuality q =
      pss_metrics::MeasureWithoutReference(mesh, cloud->GetPoints(), pss_metrics::ReferenceFreeOptions());
    // Spacings of scans in metres are millimetres: shown in mm, else in the files' units.
    std::cout << pss_metrics::DescribeWithoutReference(q, unit == 1e-6 ? 1e-3 : unit, unit == 1e-6 ? "mm" : "units");
    return 0;
  }
  if (positional.size() < 2 || positional.size() > 3)
  {
    std::cerr << Usage;
    return 2;
  }
  vtkSMPTools::SetBackend("STDThread");
  vtkSmartPointer<vtkPolyData> mesh = Read(positional[0]);
  vtkSmartPointer<vtkPolyData> reference = Read(positional[1]);
  vtkSmartPointer<vtkPolyData> cloud = positional.size() == 3 ? Read(positional[2]) : nullptr;
  const pss_metrics::MeshQuality q =
    pss_metrics::MeasureMesh(mesh, reference, cloud ? cloud->GetPoints() : nullptr, options);
  std::cout << pss_metrics::Describe(q, unit, unit == 1e-6 ? "um" : "units");
  if (loops > 0.0)
  {
    const pss_metrics::BoundaryReport b = pss_metrics::ClassifyBoundary(
      mesh, reference, cloud ? cloud->GetPoints() : nullptr, 3.0 * loops, loops);
    // Loops are millimetres across: listed in mm for files in metres, else in the files' units.
    std::cout << pss_metrics::DescribeBoundary(b, unit == 1e-6 ? 1e-3 : unit, unit == 1e-6 ? "mm" : "units");
  }
  return 0;
}
