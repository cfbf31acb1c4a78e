// SPDX-License-Identifier: BSD-3-Clause
/**
 * The sensor's viewpoint reaches the surface: a synthetic organized depth frame of the inside of a
 * sphere (radius 1, the sensor at (0, 0, 0.3) looking along +z), written as a PCD file with that
 * VIEWPOINT and read back, is projected and meshed. From the file's viewpoint every n and every
 * mesh normal faces the sensor, n . (viewpoint - x) > 0; with the viewpoint off, n points away from
 * the cloud's centroid, which on this concave cap is away from the sensor everywhere; a viewpoint
 * given above the sphere turns them outward again.
 */
#include "PCDTestUtilities.h"

#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIntArray.h"
#include "vtkPCDWriter.h"
#include "vtkPointData.h"
#include "vtkPointSetSurface.h"
#include "vtkPointSetSurfaceMesher.h"
#include "vtkPointSetSurfaceProjection.h"
#include "vtkPoints.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace pcd_test;

namespace
{

constexpr double kSensor[3] = { 0.0, 0.0, 0.3 };

// A 60 x 45 pinhole image (about 58 degrees wide) of the unit sphere seen from inside; every 7th
// pixel saw nothing (NaN), as a depth camera's invalid pixels.
std::string WriteFrame()
{
  const int width = 60, height = 45;
  vtkNew<vtkPolyData> frame;
  vtkNew<vtkPoints> points;
  vtkNew<vtkIntArray> pixels;
  pixels->SetName("Pixel");
  pixels->SetNumberOfComponents(2);
  const double focal = 0.5 * width / std::tan(29.0 * M_PI / 180.0);
  for (int row = 0; row < height; ++row)
  {
    for (int col = 0; col < width; ++col)
    {
      if ((row * width + col) % 7 == 3)
      {
        continue; // an invalid pixel: no point, the writer fills it with NaN
      }
      double d[3] = { (col - 0.5 * width) / focal, (row - 0.5 * height) / focal, 1.0 };
      const double norm = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
      for (double& c : d)
      {
        c /= norm;
      }
      // |S + t d| = 1 with t > 0: t = -S.d + sqrt((S.d)^2 - |S|^2 + 1).
      const double sd = kSensor[2] * d[2];
      const double t = -sd + std::sqrt(sd * sd - kSensor[2] * kSensor[2] + 1.0);
      points->InsertNextPoint(kSensor[0] + t * d[0], kSensor[1] + t * d[1], kSensor[2] + t * d[2]);
      const int pixel[2] = { col, row };
      pixels->InsertNextTypedTuple(pixel);
    }
  }
  frame->SetPoints(points);
  frame->GetPointData()->AddArray(pixels);
  vtkNew<vtkIdTypeArray> grid;
  grid->SetName("GridDimensions");
  grid->InsertNextValue(width);
  grid->InsertNextValue(height);
  frame->GetFieldData()->AddArray(grid);
  vtkNew<vtkDoubleArray> viewpoint;
  viewpoint->SetName("Viewpoint");
  for (double v : { kSensor[0], kSensor[1], kSensor[2], 1.0, 0.0, 0.0, 0.0 })
  {
    viewpoint->InsertNextValue(v);
  }
  frame->GetFieldData()->AddArray(viewpoint);
  const std::string path = TestPath("viewpoint_sphere.pcd");
  vtkNew<vtkPCDWriter> writer;
  writer->SetInputData(frame);
  writer->SetFileName(path.c_str());
  writer->Write();
  return path;
}

// How many rows of @p normals (at @p points) face @p viewpoint, and how many face away.
std::pair<vtkIdType, vtkIdType> Facing(vtkDataSet* points, vtkDataArray* normals, const double viewpoint[3])
{
  vtkIdType toward = 0, away = 0;
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double x[3], n[3];
    points->GetPoint(i, x);
    normals->GetTuple(i, n);
    const double side = n[0] * (viewpoint[0] - x[0]) + n[1] * (viewpoint[1] - x[1]) + n[2] * (viewpoint[2] - x[2]);
    toward += side > 0 ? 1 : 0;
    away += side < 0 ? 1 : 0;
  }
  return { toward, away };
}

} // namespace

TEST(PCDViewpoint, NormalsFaceTheSensorOfAnOrganizedFrame)
{
  const Read frame = ReadPCD(WriteFrame());
  ASSERT_TRUE(frame.ok);
  const vtkIdType n = frame.output->GetNumberOfPoints();
  ASSERT_EQ(n, 60 * 45 - (60 * 45 + 3) / 7);
  ASSERT_NE(frame.output->GetFieldData()->GetArray("Viewpoint"), nullptr);

  vtkNew<vtkPointSetSurfaceProjection> projection;
  projection->SetInputData(frame.output);
  projection->GetSurface()->SetVariantToCenterOfMass();
  projection->GetSurface()->AutomaticScaleOff();
  projection->GetSurface()->SetScaleFactor(0.1);
  const double above[3] = { 0.0, 0.0, 5.0 };
  struct Case
  {
    int mode;
    const double* viewpoint; // what every n must face
    bool facing;             // toward it (true) or away (false)
  };
  for (const Case& c : { Case{ vtkPointSetSurfaceAlgorithm::VIEWPOINT_FROM_INPUT, kSensor, true },
         Case{ vtkPointSetSurfaceAlgorithm::VIEWPOINT_OFF, kSensor, false },
         Case{ vtkPointSetSurfaceAlgorithm::VIEWPOINT_GIVEN, above, true } })
  {
    SCOPED_TRACE("ViewpointMode " + std::to_string(c.mode));
    projection->SetViewpointMode(c.mode);
    projection->SetViewpoint(const_cast<double*>(above));
    projection->Update();
    vtkPolyData* out = projection->GetOutput();
    ASSERT_EQ(out->GetNumberOfPoints(), n);
    const auto [toward, away] = Facing(out, out->GetPointData()->GetArray("Normal"), c.viewpoint);
    EXPECT_EQ(c.facing ? toward : away, n);
  }

  // The mesh of the frame, oriented by the file's viewpoint: every normal faces the sensor.
  vtkNew<vtkPointSetSurfaceMesher> mesher;
  mesher->SetInputData(frame.output);
  mesher->GetSurface()->SetVariantToCenterOfMass();
  mesher->GetSurface()->AutomaticScaleOff();
  mesher->GetSurface()->SetScaleFactor(0.1);
  mesher->Update();
  vtkPolyData* mesh = mesher->GetOutput();
  ASSERT_GT(mesh->GetNumberOfPolys(), 200);
  const auto [toward, away] = Facing(mesh, mesh->GetPointData()->GetNormals(), kSensor);
  EXPECT_EQ(toward, mesh->GetNumberOfPoints());
  EXPECT_EQ(away, 0);
  mesher->SetViewpointModeToOff();
  mesher->Update();
  const auto [towardOff, awayOff] = Facing(mesher->GetOutput(), mesher->GetOutput()->GetPointData()->GetNormals(), kSensor);
  EXPECT_EQ(awayOff, mesher->GetOutput()->GetNumberOfPoints()) << towardOff << " face the sensor without the viewpoint";
}

TEST(PCDViewpoint, NonFiniteViewpointIsAnError)
{
  vtkNew<vtkPolyData> cloud;
  vtkNew<vtkPoints> points;
  for (int i = 0; i < 100; ++i)
  {
    points->InsertNextPoint(0.1 * (i % 10), 0.1 * (i / 10), 0.0);
  }
  cloud->SetPoints(points);
  vtkNew<vtkPointSetSurfaceProjection> projection;
  vtkNew<ErrorObserver> errors;
  errors->Attach(projection);
  projection->SetInputData(cloud);
  projection->SetViewpointModeToGiven();
  projection->SetViewpoint(0.0, std::nan(""), 1.0);
  projection->Update();
  EXPECT_TRUE(errors->HasError("the viewpoint (0, nan, 1) is not finite"));
  EXPECT_EQ(projection->GetOutput()->GetNumberOfPoints(), 0);
}
