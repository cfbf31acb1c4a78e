// SPDX-License-Identifier: BSD-3-Clause
// The pss command-line tool, run as a user runs it: exit codes, messages, files, and the numbers
// in those files checked against analytic shapes and against the Stanford bunny reference mesh.
#include "CliTestUtilities.h"

#include "vtkCellLocator.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPLYReader.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkVersion.h"
#include "vtkStaticCellLocator.h"
#include "vtkXMLPolyDataReader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <memory>
#include <string>
#include <utility>
#include <sys/wait.h>
#include <vector>

using namespace pss_cli_test;

namespace
{

vtkSmartPointer<vtkPolyData> ReadVTP(const std::string& path)
{
  vtkNew<vtkXMLPolyDataReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  return reader->GetOutput();
}

bool AllFinite(vtkDataArray* a)
{
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    for (int c = 0; c < a->GetNumberOfComponents(); ++c)
    {
      if (!std::isfinite(a->GetComponent(i, c)))
      {
        return false;
      }
    }
  }
  return true;
}

double Median(std::vector<double> v)
{
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
  return v[v.size() / 2];
}

} // namespace

// --help works for the tool and every subcommand; a bad command line exits 2 with a message.
TEST(Cli, HelpAndUsageErrors)
{
  EXPECT_EQ(RunCommand(Pss() + " --help").exitCode, 0);
  for (const char* sub : { "generate", "project", "classify", "sample", "glyphs" })
  {
    const CommandResult r = RunCommand(Pss() + " " + sub + " --help");
    EXPECT_EQ(r.exitCode, 0) << sub;
    EXPECT_NE(r.output.find("--threads"), std::string::npos) << sub << " help lacks --threads";
  }
  CommandResult r = RunCommand(Pss() + " project --no-such-flag x.vtp -o y.vtp");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.output.find("unknown option"), std::string::npos) << r.output;
  r = RunCommand(Pss() + " frobnicate");
  EXPECT_EQ(r.exitCode, 2);
  r = RunCommand(Pss() + " project --h abc x.vtp -o y.vtp");
  EXPECT_EQ(r.exitCode, 2);
  EXPECT_NE(r.output.find("expects a number"), std::string::npos) << r.output;
}

// --version (and the version subcommand) names the project's version, VTK's and the copy of the
// core the loader took (or in the baseline copy its vector kernels'); --help lists it.
TEST(Cli, VersionNamesProjectVtkAndSimdPath)
{
  const std::string expected = std::string("pss ") + PSS_PROJECT_VERSION + " (PointSetSurfaces)\nVTK " +
    vtkVersion::GetVTKVersion() + "\nSIMD ";
  for (const char* spelling : { " --version", " version" })
  {
    const CommandResult r = RunCommand(Pss() + spelling);
    EXPECT_EQ(r.exitCode, 0) << spelling;
    EXPECT_EQ(r.output.rfind(expected, 0), 0u) << spelling << ": " << r.output;
    const std::string simd = r.output.substr(std::min(expected.size(), r.output.size()));
    EXPECT_TRUE(simd == "x86-64-v3\n" || simd == "avx2\n" || simd == "baseline\n") << spelling << ": " << r.output;
  }
  // The baseline copy of the core with its SSE2 kernels.
  const CommandResult forced = RunCommand("GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2 PSS_SIMD=baseline " + Pss() + " --version");
  EXPECT_EQ(forced.output, expected + "baseline\n");
  EXPECT_NE(RunCommand(Pss() + " --help").output.find("--version"), std::string::npos);
}

// Files that do not exist, empty clouds and h <= 0 fail with exit 1 and say why.
TEST(Cli, BadInputFailsWithMessage)
{
  CommandResult r = RunCommand(Pss() + " project /nonexistent/cloud.vtp -o " + TempPath("never.vtp"));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find("cannot open"), std::string::npos) << r.output;

  const std::string empty = TempPath("empty.csv");
  std::ofstream(empty) << "x,y,z\n";
  r = RunCommand(Pss() + " project " + empty + " -o " + TempPath("empty-out.vtp"));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find("empty"), std::string::npos) << r.output;

  const std::string cloud = TempPath("line.csv");
  {
    std::ofstream out(cloud);
    out << "x,y,z\n";
    for (int i = 0; i < 50; ++i)
    {
      out << 0.1 * i << ",0,0\n";
    }
  }
  r = RunCommand(Pss() + " project " + cloud + " --h 0 -o " + TempPath("h0.vtp"));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find("h must be"), std::string::npos) << r.output;
  r = RunCommand(Pss() + " project " + cloud + " --h -1 -o " + TempPath("hneg.vtp"));
  EXPECT_EQ(r.exitCode, 1);
  // A delta lattice finer than h/20 is refused when the surface is prepared (exit 1), one outside
  // [0, 1] h as a usage error (exit 2), not clamped silently.
  for (const auto& [spacing, code] : { std::pair<const char*, int>{ "0.01", 1 }, { "2", 2 }, { "-1", 2 } })
  {
    r = RunCommand(Pss() + " project " + cloud + " --variant integral --delta-lattice " + spacing + " -o " +
      TempPath("lattice.vtp"));
    EXPECT_EQ(r.exitCode, code) << spacing;
    EXPECT_NE(r.output.find("lattice"), std::string::npos) << spacing << ": " << r.output;
  }

  const std::string malformed = TempPath("malformed.csv");
  std::ofstream(malformed) << "x,y,z\n1,2,3\n4,five,6\n";
  r = RunCommand(Pss() + " project " + malformed + " -o " + TempPath("malformed.vtp"));
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find(":3:"), std::string::npos) << "the message should name line 3: " << r.output;
}

// generate -> project round trip through files: a noise-free circle of radius 50 projects onto
// itself to within the plane-fit bias h^2 / (4R) plus a margin, with no NaN and every point converged.
TEST(Cli, GenerateProjectRoundTrip)
{
  const std::string cloud = TempPath("circle.vtp");
  CommandResult r = RunCommand(Pss() + " generate --scene circle --count 2000 --size 100 -o " + cloud);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const std::string out = TempPath("circle-projected.csv");
  r = RunCommand(Pss() + " project " + cloud + " --variant com --h 1 --threads 2 --verbose -o " + out);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* stage : { "read", "index", "compute", "write" })
  {
    EXPECT_NE(r.output.find(std::string("pss: ") + stage), std::string::npos) << "--verbose lacks the " << stage << " stage";
  }
  // And the process's peak memory: at least what the program and VTK's libraries take, and far
  // below the machine's memory for a 2000-point circle.
  const std::size_t peak = r.output.find("pss: peak memory ");
  ASSERT_NE(peak, std::string::npos) << r.output;
  const double mib = std::atof(r.output.c_str() + peak + std::strlen("pss: peak memory "));
  EXPECT_GT(mib, 5.0) << r.output;
  EXPECT_LT(mib, 2048.0) << r.output;
  std::ifstream in(out);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("x,y,z,", 0), 0u) << header;
  std::size_t rows = 0;
  std::string line;
  while (std::getline(in, line))
  {
    double x = 0, y = 0;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf", &x, &y), 2) << line;
    // Bias of a plane fit on a circle: h^2 / (4R) = 0.005 at h = 1, R = 50.
    EXPECT_NEAR(std::hypot(x, y), 50.0, 0.02) << line;
    ++rows;
  }
  EXPECT_EQ(rows, 2000u);
}

namespace
{

// The x, y, z columns of a CSV the tool wrote.
std::vector<std::array<double, 3>> CsvPoints(const std::string& path)
{
  std::vector<std::array<double, 3>> rows;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line))
  {
    std::array<double, 3> p{};
    if (std::sscanf(line.c_str(), "%lf,%lf,%lf", &p[0], &p[1], &p[2]) == 3)
    {
      rows.push_back(p);
    }
  }
  return rows;
}

// Projects @p input with fixed parameters into @p output.
void Project(const std::string& input, const std::string& output)
{
  const CommandResult r = RunCommand(Pss() + " project " + input + " --variant com --h 4 -o " + output);
  ASSERT_EQ(r.exitCode, 0) << r.output;
}

} // namespace

// PCD in and out: the same cloud read from .pcd (float coordinates) and from .csv (doubles)
// projects to the same points, to float precision; so does a cloud written by the tool as .pcd.
TEST(Cli, PcdInAndOut)
{
  const std::string scene = " generate --scene sphere --count 3000 --size 100 --seed 7 -o ";
  for (const char* ext : { ".pcd", ".csv" })
  {
    const CommandResult r = RunCommand(Pss() + scene + TempPath(std::string("sphere") + ext));
    ASSERT_EQ(r.exitCode, 0) << r.output;
  }
  Project(TempPath("sphere.pcd"), TempPath("sphere-from-pcd.csv"));
  Project(TempPath("sphere.csv"), TempPath("sphere-from-csv.csv"));
  Project(TempPath("sphere.pcd"), TempPath("sphere-projected.pcd"));
  Project(TempPath("sphere-projected.pcd"), TempPath("sphere-again-from-pcd.csv"));
  Project(TempPath("sphere-from-pcd.csv"), TempPath("sphere-again-from-csv.csv"));
  for (const auto& pair : { std::make_pair("sphere-from-pcd.csv", "sphere-from-csv.csv"),
         std::make_pair("sphere-again-from-pcd.csv", "sphere-again-from-csv.csv") })
  {
    const auto a = CsvPoints(TempPath(pair.first));
    const auto b = CsvPoints(TempPath(pair.second));
    ASSERT_EQ(a.size(), 3000u) << pair.first;
    ASSERT_EQ(b.size(), 3000u) << pair.second;
    double worst = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
    {
      for (int c = 0; c < 3; ++c)
      {
        worst = std::max(worst, std::abs(a[i][c] - b[i][c]));
      }
    }
    // Coordinates of about 50 stored as float differ by up to 4e-6 from the doubles.
    EXPECT_LT(worst, 1e-3) << pair.first << " and " << pair.second;
  }
}

// The real frames of ../shared/data/real-scans: read, projected and meshed, the organized frames'
// invalid pixels reported with their count.
TEST(Cli, RealScansPcd)
{
  const std::string folder = std::string(PSS_SHARED_DATA_DIR) + "/real-scans/";
  if (!std::ifstream(folder + "test9.pcd"))
  {
    GTEST_SKIP() << "no " << folder << " (the shared data is not beside this clone)";
  }
  struct Frame
  {
    const char* name;
    const char* skipped;
  };
  for (const Frame& frame : { Frame{ "test9", "107601 of its 307200 points have NaN/Inf coordinates" },
         Frame{ "region_growing_rgb_tutorial", "47353 of its 307200 points" }, Frame{ "room_scan1", nullptr } })
  {
    const std::string out = TempPath(std::string(frame.name) + "-projected.vtp");
    // The plane procedure keeps this test a few seconds long; the mesh below uses the full one.
    const CommandResult r =
      RunCommand(Pss() + " project " + folder + frame.name + ".pcd --procedure plane --threads 2 -o " + out);
    EXPECT_EQ(r.exitCode, 0) << r.output;
    if (frame.skipped)
    {
      EXPECT_NE(r.output.find(frame.skipped), std::string::npos) << r.output;
    }
    // Every frame meshes with the defaults; the organized ones take a scale per point from their
    // grid, the room scan from its spread of scales.
    const CommandResult mesh = RunCommand(Pss() + " mesh " + folder + frame.name + ".pcd --threads 2 --verbose -o " +
      TempPath(std::string(frame.name) + "-mesh.ply"));
    EXPECT_EQ(mesh.exitCode, 0) << mesh.output;
    EXPECT_NE(mesh.output.find(" triangles"), std::string::npos) << mesh.output;
    EXPECT_NE(mesh.output.find("a scale per point"), std::string::npos) << mesh.output;
  }
}

// The Stanford bunny: projecting the merged real scans with the centre-of-mass definition moves
// no point farther than 3h, writes no NaN, and brings the points closer to the reference mesh.
TEST(Cli, StanfordBunnyScans)
{
  const std::string data = std::string(PSS_SHARED_DATA_DIR) + "/stanford-bunny";
  const std::string scans = data + "/bunny_scans_merged.ply";
  const std::string reference = data + "/bun_zipper.ply";
  if (!std::ifstream(scans) || !std::ifstream(reference))
  {
    GTEST_SKIP() << "the shared Stanford bunny data is absent (" << data << ")";
  }
  const std::string out = TempPath("bunny-projected.vtp");
  const CommandResult r = RunCommand(Pss() + " project " + scans + " --variant com --verbose -o " + out);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  std::cout << r.output;

  vtkSmartPointer<vtkPolyData> projected = ReadVTP(out);
  vtkNew<vtkPLYReader> scanReader;
  scanReader->SetFileName(scans.c_str());
  scanReader->Update();
  vtkPolyData* raw = scanReader->GetOutput();
  ASSERT_EQ(projected->GetNumberOfPoints(), raw->GetNumberOfPoints());

  vtkDataArray* scale = projected->GetFieldData()->GetArray("ScaleFactor");
  ASSERT_NE(scale, nullptr) << "the output should record the h it used";
  const double h = scale->GetComponent(0, 0);
  ASSERT_GT(h, 0.0);

  vtkPointData* pd = projected->GetPointData();
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
  {
    if (vtkDataArray* array = pd->GetArray(a))
    {
      EXPECT_TRUE(AllFinite(array)) << array->GetName() << " holds NaN or Inf";
    }
  }
  EXPECT_TRUE(AllFinite(projected->GetPoints()->GetData()));
  vtkDataArray* displacement = pd->GetArray("Displacement");
  ASSERT_NE(displacement, nullptr);
  double largest = 0.0;
  for (vtkIdType i = 0; i < displacement->GetNumberOfTuples(); ++i)
  {
    double d[3];
    displacement->GetTuple(i, d);
    largest = std::max(largest, std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
  }
  EXPECT_LE(largest, 3.0 * h) << "largest displacement " << largest / h << " h";

  vtkNew<vtkPLYReader> meshReader;
  meshReader->SetFileName(reference.c_str());
  meshReader->Update();
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(meshReader->GetOutput());
  locator->BuildLocator();
  auto distances = [&](vtkPolyData* cloud) {
    std::vector<double> d(static_cast<std::size_t>(cloud->GetNumberOfPoints()));
    for (vtkIdType i = 0; i < cloud->GetNumberOfPoints(); ++i)
    {
      double p[3], closest[3], d2 = 0.0;
      vtkIdType cell = 0;
      int sub = 0;
      cloud->GetPoint(i, p);
      locator->FindClosestPoint(p, closest, cell, sub, d2);
      d[static_cast<std::size_t>(i)] = std::sqrt(d2);
    }
    return d;
  };
  const double before = Median(distances(raw));
  const double after = Median(distances(projected));
  std::cout << "bunny: h = " << h << ", largest displacement " << largest / h << " h, median distance to bun_zipper "
            << before << " -> " << after << "\n";
  EXPECT_LT(after, before);
}

TEST(Cli, MeshWritesEveryMeshFormat)
{
  const std::string cloud = TempPath("mesh-sphere-cloud.vtp");
  CommandResult r = RunCommand(Pss() + " generate --scene sphere --dimension 3 --count 8000 --size 20 --noise 0.01 -o " + cloud);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* ext : { ".vtp", ".ply", ".stl", ".obj" })
  {
    const std::string out = TempPath(std::string("mesh-sphere") + ext);
    std::remove(out.c_str());
    r = RunCommand(Pss() + " mesh " + cloud + " --h 1 --verbose -o " + out);
    ASSERT_EQ(r.exitCode, 0) << ext << ": " << r.output;
    std::ifstream written(out, std::ios::binary | std::ios::ate);
    EXPECT_GT(static_cast<long long>(written.tellg()), 10000) << ext;
    // --verbose: the stages and the counts of the mesh issue.
    for (const char* text : { "mesh stages: band", "triangles", "BandCells", "Components 1", "BoundaryEdges 0" })
    {
      EXPECT_NE(r.output.find(text), std::string::npos) << ext << ": " << text << "\n" << r.output;
    }
  }
}

TEST(Cli, MeshRefusesBadCellsAndBands)
{
  const std::string cloud = TempPath("mesh-plane.vtp");
  CommandResult r = RunCommand(Pss() + " generate --scene plane --dimension 3 --count 2000 --size 10 -o " + cloud);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  for (const char* bad : { "--cell 0", "--cell -1", "--cell nan", "--band 0", "--cell 1e9" })
  {
    r = RunCommand(Pss() + " mesh " + cloud + " --h 1 " + bad + " -o " + TempPath("never-mesh.vtp"));
    EXPECT_EQ(r.exitCode, 1) << bad << ": " << r.output;
    EXPECT_NE(r.output.find("must be within"), std::string::npos) << bad << ": " << r.output;
  }
  // Allowed, but a band of about 10^9 cells: refused with the count before it is allocated.
  r = RunCommand(Pss() + " mesh " + cloud + " --h 1 --cell 0.05 --band 100 -o " + TempPath("never-mesh.vtp"));
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("cells (the limit is"), std::string::npos) << r.output;
  r = RunCommand(Pss() + " mesh " + cloud + " --h 0 -o " + TempPath("never-mesh.vtp"));
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("h must be"), std::string::npos) << r.output;
}

// The surface scenes are 3D unless --dimension 2 asks for their cross-sections (a sphere of radius
// Size/2, or its equator); the curve scenes stay 2D.
TEST(Cli, GenerateSurfaceScenesIn3DByDefault)
{
  struct Case
  {
    const char* args;
    int axes; ///< how many axes the points spread along: the 3D sphere 3, its equator 2, the plane 2, its cross-section 1
  };
  for (const Case& c : { Case{ "--scene sphere", 3 }, Case{ "--scene plane", 2 }, Case{ "--scene two-sheets", 3 },
         Case{ "--scene sphere --dimension 2", 2 }, Case{ "--scene plane --dimension 2", 1 },
         Case{ "--scene circle", 2 }, Case{ "--scene noisy-curve", 2 } })
  {
    const std::string cloud = TempPath("generated-dimension.vtp");
    const CommandResult r = RunCommand(Pss() + " generate " + c.args + " --count 500 --size 20 -o " + cloud);
    ASSERT_EQ(r.exitCode, 0) << c.args << ": " << r.output;
    vtkSmartPointer<vtkPolyData> pd = ReadVTP(cloud);
    ASSERT_EQ(pd->GetNumberOfPoints(), 500) << c.args;
    double b[6];
    pd->GetBounds(b);
    const int axes = (b[1] - b[0] > 1.0) + (b[3] - b[2] > 1.0) + (b[5] - b[4] > 1.0);
    EXPECT_EQ(axes, c.axes) << c.args << ": bounds " << b[0] << " " << b[1] << " " << b[2] << " " << b[3] << " "
                            << b[4] << " " << b[5];
    if (std::string(c.args) == "--scene sphere")
    {
      for (vtkIdType i = 0; i < pd->GetNumberOfPoints(); ++i)
      {
        double p[3];
        pd->GetPoint(i, p);
        ASSERT_NEAR(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]), 10.0, 1e-9) << i;
      }
    }
  }
}
