// SPDX-License-Identifier: BSD-3-Clause
// `pss generate --scene depth-camera`: an organized 640 x 480 frame, written as PCD with its
// WIDTH, HEIGHT and VIEWPOINT and as .vtp with the same field data, that pss reads back (its NaN
// pixels skipped and counted) and orients n toward the sensor from; the mesh of such a frame with
// cells that follow its scale; and the other orientation of n, propagated over neighbours.
#include "CliTestUtilities.h"

#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkXMLPolyDataReader.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

using namespace pss_cli_test;

namespace
{

vtkSmartPointer<vtkPolyData> ReadFrame(const std::string& path)
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader->GetOutput();
}

// The header lines of a PCD file, keyword -> the rest of the line, up to DATA.
std::map<std::string, std::string> PcdHeader(const std::string& path)
{
  std::map<std::string, std::string> header;
  std::ifstream in(path, std::ios::binary);
  std::string line;
  while (std::getline(in, line))
  {
    if (line.empty() || line[0] == '#')
    {
      continue;
    }
    const auto space = line.find(' ');
    const std::string key = line.substr(0, space);
    header[key] = space == std::string::npos ? "" : line.substr(space + 1);
    if (key == "DATA")
    {
      break;
    }
  }
  return header;
}

} // namespace

TEST(Cli, GenerateDepthCamera)
{
  const std::string pcd = TempPath("depth-camera.pcd");
  const std::string vtp = TempPath("depth-camera.vtp");
  const auto t0 = std::chrono::steady_clock::now();
  CommandResult r = RunCommand(Pss() + " generate --scene depth-camera -o " + pcd);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::printf("[measured] pss generate --scene depth-camera -o frame.pcd: %.2f s\n", seconds);
  std::map<std::string, std::string> header = PcdHeader(pcd);
  EXPECT_EQ(header["WIDTH"], "640");
  EXPECT_EQ(header["HEIGHT"], "480");
  EXPECT_EQ(header["POINTS"], "307200");
  EXPECT_EQ(header["VIEWPOINT"], "0 0 0 1 0 0 0");
  EXPECT_NE(header["FIELDS"].find("SurfaceId"), std::string::npos) << header["FIELDS"];
  EXPECT_NE(header["FIELDS"].find("NoiseSigma"), std::string::npos) << header["FIELDS"];

  r = RunCommand(Pss() + " generate --scene depth-camera -o " + vtp);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  vtkSmartPointer<vtkPolyData> frame = ReadFrame(vtp);
  ASSERT_EQ(frame->GetNumberOfPoints(), 307200);
  vtkDataArray* grid = frame->GetFieldData()->GetArray("GridDimensions");
  vtkDataArray* viewpoint = frame->GetFieldData()->GetArray("Viewpoint");
  ASSERT_NE(grid, nullptr);
  ASSERT_NE(viewpoint, nullptr);
  EXPECT_EQ(grid->GetComponent(0, 0), 640);
  EXPECT_EQ(grid->GetComponent(1, 0), 480);
  EXPECT_EQ(viewpoint->GetNumberOfValues(), 7);
  for (const char* name : { "Pixel", "SurfaceId", "NoiseSigma", "DistanceToShape" })
  {
    EXPECT_NE(frame->GetPointData()->GetArray(name), nullptr) << name;
  }

  // Start points on the measured pixels; the projection reads the PCD file back.
  long long nan = 0;
  std::ostringstream starts;
  starts.precision(17);
  starts << "x,y,z\n";
  int count = 0;
  for (vtkIdType i = 0; i < frame->GetNumberOfPoints(); ++i)
  {
    double p[3];
    frame->GetPoint(i, p);
    if (!std::isfinite(p[0]))
    {
      ++nan;
    }
    else if (i % 1999 == 0)
    {
      starts << p[0] << "," << p[1] << "," << p[2] << "\n";
      ++count;
    }
  }
  const std::string startPath = TempPath("depth-camera-starts.csv");
  std::ofstream(startPath) << starts.str();
  const std::string projected = TempPath("depth-camera-projected.vtp");
  r = RunCommand(Pss() + " project " + pcd + " --start " + startPath + " --variant com --threads 2 -o " + projected);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find(std::to_string(nan) + " of its 307200 points have NaN"), std::string::npos) << r.output;
  vtkSmartPointer<vtkPolyData> out = ReadFrame(projected);
  ASSERT_EQ(out->GetNumberOfPoints(), count);
  vtkDataArray* normals = out->GetPointData()->GetArray("Normal");
  ASSERT_NE(normals, nullptr);
  int defined = 0, toward = 0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double n[3], x[3];
    normals->GetTuple(i, n);
    out->GetPoint(i, x);
    if (std::isfinite(n[0]))
    {
      ++defined;
      toward += n[0] * x[0] + n[1] * x[1] + n[2] * x[2] < 0.0 ? 1 : 0; // n . (sensor - x) > 0
    }
  }
  EXPECT_GT(defined, count * 9 / 10);
  EXPECT_EQ(toward, defined) << "n faces the file's viewpoint";

  // A smaller image, and images pss refuses.
  r = RunCommand(Pss() + " generate --scene depth-camera --image 160x120 --depth-noise 0 -o " + vtp);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(ReadFrame(vtp)->GetNumberOfPoints(), 160 * 120);
  for (const char* bad : { "0x5", "640", "640x480x3", "20000x10", "axb" })
  {
    r = RunCommand(Pss() + " generate --scene depth-camera --image " + bad + " -o " + vtp);
    EXPECT_EQ(r.exitCode, 2) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("--image expects"), std::string::npos) << r.output;
  }
}

// pss mesh on a depth frame: cells that follow the scale per point by default, one grid with
// --regular-cells; both one crack-free surface per object.
TEST(Cli, MeshCellsFollowTheScaleUnlessRegular)
{
  const std::string frame = TempPath("small-depth-camera.vtp");
  CommandResult r = RunCommand(Pss() + " generate --scene depth-camera --image 160x120 -o " + frame);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  auto levels = [&](const std::string& flags, const std::string& name) {
    const std::string out = TempPath(name);
    const CommandResult m = RunCommand(Pss() + " mesh " + frame + " --threads 2 " + flags + " -o " + out);
    EXPECT_EQ(m.exitCode, 0) << m.output;
    vtkSmartPointer<vtkPolyData> mesh = ReadFrame(out);
    vtkDataArray* cellLevels = mesh->GetFieldData()->GetArray("CellLevels");
    vtkDataArray* nonManifold = mesh->GetFieldData()->GetArray("NonManifoldEdges");
    EXPECT_NE(cellLevels, nullptr);
    EXPECT_NE(nonManifold, nullptr);
    EXPECT_GT(mesh->GetNumberOfPolys(), 1000);
    EXPECT_EQ(nonManifold ? nonManifold->GetComponent(0, 0) : -1.0, 0.0);
    return cellLevels ? cellLevels->GetComponent(0, 0) : 0.0;
  };
  EXPECT_GT(levels("", "adaptive-cells.vtp"), 1.0);
  EXPECT_EQ(levels("--regular-cells", "regular-cells.vtp"), 1.0);
}

// pss project --propagate-normals: the oriented normals of a sphere, every one outward; a graph
// of no neighbours is refused.
TEST(Cli, ProjectPropagatesNormals)
{
  const std::string cloud = TempPath("propagate-sphere.vtp");
  const std::string out = TempPath("propagate-sphere-normals.vtp");
  CommandResult r = RunCommand(Pss() + " generate --scene sphere --dimension 3 --count 2000 --size 20 --noise 0.1 -o " + cloud);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  r = RunCommand(Pss() + " project " + cloud + " --procedure plane --propagate-normals --normal-neighbors 12 -o " + out);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  vtkSmartPointer<vtkPolyData> projected = ReadFrame(out);
  vtkDataArray* normals = projected->GetPointData()->GetArray("Normal");
  ASSERT_NE(normals, nullptr);
  ASSERT_EQ(projected->GetNumberOfPoints(), 2000);
  vtkIdType outward = 0;
  for (vtkIdType i = 0; i < projected->GetNumberOfPoints(); ++i)
  {
    double n[3], x[3];
    normals->GetTuple(i, n);
    projected->GetPoint(i, x);
    outward += n[0] * x[0] + n[1] * x[1] + n[2] * x[2] > 0.0 ? 1 : 0;
  }
  EXPECT_EQ(outward, projected->GetNumberOfPoints());
  r = RunCommand(Pss() + " project " + cloud + " --propagate-normals --normal-neighbors 0 -o " + out);
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find("--normal-neighbors must be within [1, 100]"), std::string::npos) << r.output;
}

TEST(Cli, ApssAndRimlsProjectOntoASphere)
{
  const std::string cloud = TempPath("apss-sphere.vtp");
  const std::string out = TempPath("apss-sphere-projected.vtp");
  CommandResult r = RunCommand(Pss() + " generate --scene sphere --dimension 3 --count 2000 --size 20 --noise 0 -o " + cloud);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const std::string variant : { "apss", "rimls" })
  {
    r = RunCommand(Pss() + " project " + cloud + " --variant " + variant +
      " --procedure plane --sphericity 1 --sigma-n 0.75 --sigma-r 0.5 --robust-refits 3 -o " + out);
    ASSERT_EQ(r.exitCode, 0) << r.output;
    vtkSmartPointer<vtkPolyData> projected = ReadFrame(out);
    ASSERT_EQ(projected->GetNumberOfPoints(), 2000);
    vtkDataArray* converged = projected->GetPointData()->GetArray("Converged");
    ASSERT_NE(converged, nullptr);
    for (vtkIdType i = 0; i < projected->GetNumberOfPoints(); ++i)
    {
      ASSERT_EQ(converged->GetComponent(i, 0), 1.0) << variant << " point " << i;
    }
  }
  r = RunCommand(Pss() + " project " + cloud + " --variant apss --sphericity 2 -o " + out);
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("--sphericity"), std::string::npos) << r.output;
  r = RunCommand(Pss() + " project " + cloud + " --variant rimls --robust-refits 2.5 -o " + out);
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find("--robust-refits"), std::string::npos) << r.output;
}
