// SPDX-License-Identifier: BSD-3-Clause
/**
 * The cloud source's DEPTH_CAMERA scene: the core's frame (pss::generateDepthFrame) with the
 * field data and point arrays of an organized cloud read by vtkPCDReader, so that vtkPCDWriter
 * writes it as an organized PCD file with its viewpoint, and the filters orient n toward the
 * sensor it came from.
 */
#include "ErrorObserver.h"
#include "FilterTestUtilities.h"

#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPCDReader.h"
#include "vtkPCDWriter.h"
#include "vtkPointData.h"
#include "vtkPointSetSurface.h"
#include "vtkPointSetSurfaceCloudSource.h"
#include "vtkPointSetSurfaceProjection.h"
#include "vtkPolyData.h"

#include "pss/SyntheticClouds.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

using namespace pss_test;

namespace
{

bool FinitePoint(vtkPolyData* pd, vtkIdType i)
{
  const Point p = Coordinates(pd, i);
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

} // namespace

TEST(FilterDepthCamera, OrganizedFrameWithItsTruth)
{
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  source->SetSceneToDepthCamera();
  EXPECT_STREQ(source->GetSceneAsString(), "depth-camera");
  source->SetNumberOfPoints(10); // ignored: the image fixes the count
  source->SetSeed(3);
  source->Update();
  vtkPolyData* out = source->GetOutput();
  const vtkIdType n = 640 * 480;
  ASSERT_EQ(out->GetNumberOfPoints(), n);
  EXPECT_EQ(out->GetNumberOfVerts(), n);

  auto* grid = vtkIdTypeArray::SafeDownCast(out->GetFieldData()->GetArray("GridDimensions"));
  ASSERT_NE(grid, nullptr) << "GridDimensions is vtkPCDReader's vtkIdTypeArray";
  ASSERT_EQ(grid->GetNumberOfValues(), 2);
  EXPECT_EQ(grid->GetValue(0), 640);
  EXPECT_EQ(grid->GetValue(1), 480);
  vtkDataArray* viewpoint = out->GetFieldData()->GetArray("Viewpoint");
  ASSERT_NE(viewpoint, nullptr);
  ASSERT_EQ(viewpoint->GetNumberOfValues(), 7);
  const double identity[7] = { 0, 0, 0, 1, 0, 0, 0 };
  for (vtkIdType k = 0; k < 7; ++k)
  {
    EXPECT_EQ(viewpoint->GetComponent(k, 0), identity[k]) << k;
  }

  auto* pixel = vtkIntArray::SafeDownCast(out->GetPointData()->GetArray("Pixel"));
  auto* surface = vtkIntArray::SafeDownCast(out->GetPointData()->GetArray("SurfaceId"));
  vtkDataArray* sigma = out->GetPointData()->GetArray("NoiseSigma");
  ASSERT_NE(pixel, nullptr);
  ASSERT_NE(surface, nullptr);
  ASSERT_NE(sigma, nullptr);
  ASSERT_EQ(pixel->GetNumberOfComponents(), 2);
  EXPECT_STREQ(out->GetPointData()->GetScalars()->GetName(), "DistanceToShape");

  // The same frame as the core's, value for value.
  pss::CloudSpec spec;
  spec.scene = pss::Scene::DepthCamera;
  spec.seed = 3;
  const pss::DepthFrame frame = pss::generateDepthFrame(spec);
  vtkIdType nan = 0;
  vtkIdType perSurface[pss::DepthSurfaceCount] = {};
  for (vtkIdType i = 0; i < n; ++i)
  {
    const auto k = static_cast<std::size_t>(i);
    ASSERT_EQ(pixel->GetTypedComponent(i, 0), static_cast<int>(i % 640)) << "column";
    ASSERT_EQ(pixel->GetTypedComponent(i, 1), static_cast<int>(i / 640)) << "row";
    ASSERT_EQ(surface->GetValue(i), static_cast<int>(frame.pixels[k].surface));
    ASSERT_EQ(sigma->GetTuple1(i), frame.pixels[k].sigma);
    const Point p = Coordinates(out, i);
    const bool valid = FinitePoint(out, i);
    ASSERT_EQ(valid, frame.pixels[k].state == pss::PixelState::Valid);
    if (!valid)
    {
      ++nan;
      EXPECT_TRUE(std::isnan(Value(out, "DistanceToShape", i)));
      continue;
    }
    ++perSurface[surface->GetValue(i)];
    ASSERT_EQ(p[0], frame.points[k].x());
    ASSERT_EQ(p[2], frame.points[k].z());
    // Within 6 sigma along the ray plus a quantization step (3 mm at 1 m) of the true scene.
    ASSERT_LT(Value(out, "DistanceToShape", i), 1.2 * (6.0 * sigma->GetTuple1(i) + 0.003 * p[2] * p[2]));
  }
  std::printf("[measured] depth camera 640 x 480, seed 3: %lld NaN; valid pixels: table %lld, box %lld, "
              "cylinder %lld, sphere %lld\n",
    static_cast<long long>(nan), static_cast<long long>(perSurface[1]), static_cast<long long>(perSurface[2]),
    static_cast<long long>(perSurface[3]), static_cast<long long>(perSurface[4]));
  EXPECT_GT(nan, 10000);
  for (int s = 1; s < pss::DepthSurfaceCount; ++s)
  {
    EXPECT_GE(perSurface[s], 2000) << pss::depthSurfaceName(static_cast<pss::DepthSurface>(s));
  }
}

// Written by vtkPCDWriter and read back by vtkPCDReader: a 640 x 480 organized file with the
// sensor's viewpoint, whose NaN pixels the reader skips and counts, and whose kept points keep
// their pixels and arrays.
TEST(FilterDepthCamera, PCDRoundTrip)
{
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  source->SetSceneToDepthCamera();
  source->Update();
  vtkPolyData* frame = source->GetOutput();
  const std::string path = std::string(PSS_BINARY_DIR) + "/Testing/depth-camera-frame.pcd";
  vtkNew<vtkPCDWriter> writer;
  writer->SetInputData(frame);
  writer->SetFileName(path.c_str());
  writer->SetDataModeToBinaryCompressed();
  ASSERT_EQ(writer->Write(), 1);

  vtkNew<vtkPCDReader> reader;
  reader->SetFileName(path.c_str());
  reader->Update();
  vtkPolyData* back = reader->GetOutput();
  vtkDataArray* grid = back->GetFieldData()->GetArray("GridDimensions");
  ASSERT_NE(grid, nullptr);
  EXPECT_EQ(grid->GetComponent(0, 0), 640);
  EXPECT_EQ(grid->GetComponent(1, 0), 480);
  vtkDataArray* viewpoint = back->GetFieldData()->GetArray("Viewpoint");
  ASSERT_NE(viewpoint, nullptr);
  EXPECT_EQ(viewpoint->GetComponent(3, 0), 1.0) << "qw of the identity";
  vtkIdType nan = 0;
  for (vtkIdType i = 0; i < frame->GetNumberOfPoints(); ++i)
  {
    nan += FinitePoint(frame, i) ? 0 : 1;
  }
  EXPECT_EQ(reader->GetNumberOfPointsInFile(), 640 * 480);
  EXPECT_EQ(reader->GetNumberOfSkippedPoints(), nan);
  ASSERT_EQ(back->GetNumberOfPoints(), 640 * 480 - nan);
  vtkDataArray* pixel = back->GetPointData()->GetArray("Pixel");
  vtkDataArray* surface = back->GetPointData()->GetArray("SurfaceId");
  ASSERT_NE(pixel, nullptr);
  ASSERT_NE(surface, nullptr);
  for (vtkIdType j = 0; j < back->GetNumberOfPoints(); j += 101)
  {
    const vtkIdType i = static_cast<vtkIdType>(pixel->GetComponent(j, 1)) * 640 + static_cast<vtkIdType>(pixel->GetComponent(j, 0));
    const Point a = Coordinates(frame, i), b = Coordinates(back, j);
    for (int c = 0; c < 3; ++c)
    {
      EXPECT_NEAR(b[c], a[c], 1e-6 * std::abs(a[c]) + 1e-7) << "float coordinates in the file";
    }
    EXPECT_EQ(surface->GetComponent(j, 0), Value(frame, "SurfaceId", i));
  }
  std::remove(path.c_str());
}

// The filters find the frame's viewpoint: every n points toward the sensor.
TEST(FilterDepthCamera, NormalsFaceTheSensor)
{
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  source->SetSceneToDepthCamera();
  source->SetImageWidth(160);
  source->SetImageHeight(120);
  source->Update();
  vtkPolyData* frame = source->GetOutput();
  ASSERT_EQ(frame->GetNumberOfPoints(), 160 * 120);
  std::vector<Point> starts;
  for (vtkIdType i = 0; i < frame->GetNumberOfPoints(); i += 97)
  {
    if (FinitePoint(frame, i))
    {
      starts.push_back(Coordinates(frame, i));
    }
  }
  vtkNew<vtkPointSetSurfaceProjection> projection;
  projection->SetInputConnection(source->GetOutputPort());
  projection->SetStartPointsData(MakePoints(starts));
  projection->GetSurface()->SetVariantToCenterOfMass();
  projection->Update();
  vtkPolyData* out = projection->GetOutput();
  ASSERT_EQ(out->GetNumberOfPoints(), static_cast<vtkIdType>(starts.size()));
  vtkIdType toward = 0, defined = 0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    const Point n = { Value(out, "Normal", i, 0), Value(out, "Normal", i, 1), Value(out, "Normal", i, 2) };
    if (!std::isfinite(n[0]))
    {
      continue;
    }
    ++defined;
    const Point x = Coordinates(out, i);
    toward += Dot(n, Sub({ 0.0, 0.0, 0.0 }, x)) > 0.0 ? 1 : 0;
  }
  EXPECT_GT(defined, static_cast<vtkIdType>(starts.size()) * 9 / 10);
  EXPECT_EQ(toward, defined);
}

TEST(FilterDepthCamera, BadSettings)
{
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  vtkNew<ErrorObserver> log;
  log->Attach(source);
  source->SetSceneToDepthCamera();
  source->SetImageWidth(0);
  EXPECT_EQ(source->GetImageWidth(), 1);
  source->SetImageHeight(100000);
  EXPECT_EQ(source->GetImageHeight(), 16384);
  source->SetDepthNoise(-1.0);
  EXPECT_EQ(source->GetDepthNoise(), 0.0);
  source->SetImageWidth(16384); // 2.7e8 pixels: refused before anything is allocated
  source->Update();
  EXPECT_TRUE(log->HasError("at most 1e8"));
  EXPECT_EQ(source->GetOutput()->GetNumberOfPoints(), 0);
  log->Clear();
  source->SetImageWidth(4);
  source->SetImageHeight(3);
  source->Update();
  EXPECT_TRUE(log->Errors.empty());
  EXPECT_EQ(source->GetOutput()->GetNumberOfPoints(), 12);
}
