// SPDX-License-Identifier: BSD-3-Clause
/**
 * The depth-camera and room frames of ../shared/data/real-scans read with vtkPCDReader: the
 * point counts (finite and NaN) add up to the header's POINTS, the organized frames keep their
 * 640 x 480 image and every point's pixel, the viewpoint is recovered. Skipped without the data.
 */
#include "PCDTestUtilities.h"

#include "vtkFieldData.h"
#include "vtkPointData.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

using namespace pcd_test;

namespace
{

struct Frame
{
  const char* file;
  bool organized;
  const char* colors; ///< the colour array the file's rgb / rgba field becomes
  double viewpoint[7];
};

// The header's POINTS line, read here with a plain text scan rather than by the reader under test.
long HeaderPoints(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::string line;
  while (std::getline(in, line) && line.rfind("DATA", 0) != 0)
  {
    if (line.rfind("POINTS ", 0) == 0)
    {
      return std::stol(line.substr(7));
    }
  }
  return -1;
}

} // namespace

TEST(PCDRealScans, ReadWithCountsGridAndViewpoint)
{
  const std::string folder = std::string(PSS_SHARED_DATA_DIR) + "/real-scans/";
  const Frame frames[] = {
    { "test9.pcd", true, "RGBA", { 0, 0, 0, 1, 0, 0, 0 } },
    { "region_growing_rgb_tutorial.pcd", true, "RGB", { 0, 0, 0, 0, 1, 0, 0 } },
    { "room_scan1.pcd", false, nullptr, { 0, 0, 0, 1, 0, 0, 0 } },
  };
  if (!std::ifstream(folder + frames[0].file))
  {
    GTEST_SKIP() << "no " << folder << " (the shared data is not beside this clone)";
  }
  for (const Frame& frame : frames)
  {
    SCOPED_TRACE(frame.file);
    const std::string path = folder + frame.file;
    const long points = HeaderPoints(path);
    const Read finite = ReadPCD(path);
    ASSERT_TRUE(finite.ok) << finite.errors->Errors.front();
    const Read all = ReadPCD(path, false);
    ASSERT_TRUE(all.ok);
    const vtkIdType kept = finite.output->GetNumberOfPoints();
    const vtkIdType skipped = finite.reader->GetNumberOfSkippedPoints();
    std::printf("%s: POINTS %ld, %lld finite, %lld NaN skipped\n", frame.file, points, static_cast<long long>(kept),
      static_cast<long long>(skipped));
    EXPECT_EQ(kept + skipped, points);
    EXPECT_EQ(all.output->GetNumberOfPoints(), points);
    EXPECT_GT(kept, 50000);
    // Every kept point is finite, and the skipped ones really are not.
    vtkIdType nonFinite = 0;
    for (vtkIdType i = 0; i < all.output->GetNumberOfPoints(); ++i)
    {
      double p[3];
      all.output->GetPoint(i, p);
      nonFinite += !(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]));
    }
    EXPECT_EQ(nonFinite, skipped);
    vtkDataArray* grid = finite.output->GetFieldData()->GetArray("GridDimensions");
    ASSERT_NE(grid, nullptr);
    vtkDataArray* pixel = finite.output->GetPointData()->GetArray("Pixel");
    if (frame.organized)
    {
      EXPECT_GT(skipped, 0);
      EXPECT_EQ(grid->GetComponent(0, 0), 640);
      EXPECT_EQ(grid->GetComponent(1, 0), 480);
      ASSERT_NE(pixel, nullptr);
      // The pixel of each kept point is where the full image has that very point.
      for (vtkIdType j = 0; j < kept; j += 997)
      {
        const vtkIdType i =
          static_cast<vtkIdType>(pixel->GetComponent(j, 1)) * 640 + static_cast<vtkIdType>(pixel->GetComponent(j, 0));
        double a[3], b[3];
        finite.output->GetPoint(j, a);
        all.output->GetPoint(i, b);
        EXPECT_EQ(a[2], b[2]);
      }
      ASSERT_NE(finite.output->GetPointData()->GetArray(frame.colors), nullptr);
    }
    else
    {
      EXPECT_EQ(grid->GetComponent(0, 0), points);
      EXPECT_EQ(grid->GetComponent(1, 0), 1);
      EXPECT_EQ(pixel, nullptr);
    }
    vtkDataArray* viewpoint = finite.output->GetFieldData()->GetArray("Viewpoint");
    ASSERT_NE(viewpoint, nullptr);
    for (vtkIdType k = 0; k < 7; ++k)
    {
      EXPECT_EQ(viewpoint->GetComponent(k, 0), frame.viewpoint[k]);
    }
  }
}
