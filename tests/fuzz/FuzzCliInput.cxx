// SPDX-License-Identifier: BSD-3-Clause
/**
 * libFuzzer target over the pss tool's input path: the first byte picks a file extension (.csv,
 * .xyz, .txt, .ply, .vtp, .vtu, .vti: index 0 to 6, modulo 7), the rest is written to a file of
 * that name and read with pss_cli::ReadDataSet, exactly as `pss project FILE` reads it. Then, as
 * the tool would, the points read are indexed and a few of them projected with the automatic h.
 *
 * Contracts checked beyond ASan/UBSan (a broken one aborts, i.e. is a crash for libFuzzer):
 * - ReadDataSet either returns a dataset or throws std::runtime_error (a readable message, exit 1
 *   in the tool); it never returns null and nothing else escapes;
 * - text tables round-trip: writing what was read as .csv and reading it back gives the same
 *   number of points with the same coordinates, to the bit (the writer prints %.17g).
 * VTK's own readers are not instrumented (they are Debian's libraries); crashes inside them would
 * still show, as segfaults.
 */
#include "FuzzContract.h"
#include "PssIO.h"

#include "pss/Core.h"

#include "vtkDataSet.h"
#include "vtkObject.h"
#include "vtkSmartPointer.h"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <vector>

const char* const FuzzTargetName = "pss_fuzz_cli_input";

namespace
{


std::string Folder;

void WriteFile(const std::string& path, const std::uint8_t* data, std::size_t size)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  if (!out)
  {
    FuzzFail("cannot write the fuzz input to a temporary file", __LINE__);
  }
}

bool SameBits(double a, double b)
{
  return std::memcmp(&a, &b, sizeof(double)) == 0 || (std::isnan(a) && std::isnan(b));
}

std::vector<pss::Vec3> Points(vtkDataSet* data, vtkIdType limit)
{
  std::vector<pss::Vec3> out;
  const vtkIdType n = std::min(limit, data->GetNumberOfPoints());
  for (vtkIdType i = 0; i < n; ++i)
  {
    double p[3];
    data->GetPoint(i, p);
    out.emplace_back(p[0], p[1], p[2]);
  }
  return out;
}

// What `pss project` does with a cloud, on at most 64 of its points and 4 start points.
void Project(const std::vector<pss::Vec3>& cloud)
{
  const pss::PointIndex index(cloud, pss::detectDimension(cloud));
  if (index.empty())
  {
    return;
  }
  pss::SurfaceParameters params;
  params.h = pss::estimateScale(index, 10, 1.0);
  if (!(params.h > 0.0) || !std::isfinite(params.h))
  {
    params.h = 1.0;
  }
  std::unique_ptr<pss::SurfaceDefinition> surface;
  try
  {
    surface = pss::makeSurface(pss::Variant::CenterOfMass, index, params);
  }
  catch (const std::invalid_argument&)
  {
    return;
  }
  pss::ProjectionOptions options;
  options.maxIterations = 8;
  pss::Workspace ws;
  for (std::size_t i = 0; i < cloud.size() && i < 4; ++i)
  {
    const pss::ProjectionResult r = pss::project(*surface, cloud[i], options, ws);
    PSS_FUZZ_CHECK((r.reason == pss::StopReason::InvalidInput) == !pss::isFinite(cloud[i]));
  }
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  // VTK's readers report malformed files on stderr; thousands of messages a second are noise.
  vtkObject::GlobalWarningDisplayOff();
  Folder = MakeScratchFolder("pss-fuzz-cli");
  std::atexit([]() {
    for (const char* ext : { ".csv", ".xyz", ".txt", ".ply", ".vtp", ".vtu", ".vti", ".roundtrip.csv" })
    {
      std::remove((Folder + "/input" + ext).c_str());
    }
    rmdir(Folder.c_str());
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size == 0)
  {
    return 0;
  }
  // New extensions go at the end: the committed corpus's first bytes keep their meaning.
  static const char* const extensions[] = { ".csv", ".xyz", ".txt", ".ply", ".vtp", ".vtu", ".vti" };
  const std::string ext = extensions[data[0] % (sizeof(extensions) / sizeof(extensions[0]))];
  const std::string path = Folder + "/input" + ext;
  WriteFile(path, data + 1, size - 1);

  vtkSmartPointer<vtkDataSet> read;
  try
  {
    read = pss_cli::ReadDataSet(path);
  }
  catch (const std::runtime_error&)
  {
    return 0; // the tool prints the message and exits 1
  }
  PSS_FUZZ_CHECK(read != nullptr);

  const bool text = ext == ".csv" || ext == ".xyz" || ext == ".txt";
  if (text && read->GetNumberOfPoints() <= 4096)
  {
    const std::string copy = Folder + "/input.roundtrip.csv";
    pss_cli::WriteDataSet(read, copy);
    vtkSmartPointer<vtkDataSet> again = pss_cli::ReadDataSet(copy);
    PSS_FUZZ_CHECK(again != nullptr);
    PSS_FUZZ_CHECK(again->GetNumberOfPoints() == read->GetNumberOfPoints());
    for (vtkIdType i = 0; i < read->GetNumberOfPoints(); ++i)
    {
      double a[3], b[3];
      read->GetPoint(i, a);
      again->GetPoint(i, b);
      PSS_FUZZ_CHECK(SameBits(a[0], b[0]) && SameBits(a[1], b[1]) && SameBits(a[2], b[2]));
    }
  }
  Project(Points(read, 64));
  return 0;
}
