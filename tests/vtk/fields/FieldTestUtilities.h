// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file FieldTestUtilities.h
 * @brief Clouds with known geometry as vtkPolyData, an error/warning observer, and small checks
 *        shared by the field-sampler and implicit-function tests.
 *
 * Every cloud is a lattice of spacing 0.1 h along a line or a circle: Gaussian-weighted sums over
 * it equal their continuum integrals to far better than any tolerance used here (Poisson
 * summation: relative error ~exp(-pi^2 h^2 / s^2) ~ 1e-400 at s = 0.1 h).
 */
#pragma once

#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataSet.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cmath>
#include <string>
#include <vector>

namespace pss_field_test
{

constexpr double kPi = 3.14159265358979323846;

/// Points (i s, 0, 0) for |i s| <= halfLength: a straight line along x (2D, z = 0).
inline vtkSmartPointer<vtkPolyData> LineCloud(double halfLength, double spacing)
{
  const long n = std::lround(halfLength / spacing);
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  for (long i = -n; i <= n; ++i)
  {
    pts->InsertNextPoint(static_cast<double>(i) * spacing, 0.0, 0.0);
  }
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(pts);
  return cloud;
}

/// The full circle |p| = R in the xy-plane, centred at the origin, at arc-length spacing ~s.
inline vtkSmartPointer<vtkPolyData> CircleCloud(double R, double spacing)
{
  const long n = std::lround(2.0 * kPi * R / spacing);
  vtkNew<vtkPoints> pts;
  pts->SetDataTypeToDouble();
  for (long i = 0; i < n; ++i)
  {
    const double phi = 2.0 * kPi * static_cast<double>(i) / static_cast<double>(n);
    pts->InsertNextPoint(R * std::cos(phi), R * std::sin(phi), 0.0);
  }
  auto cloud = vtkSmartPointer<vtkPolyData>::New();
  cloud->SetPoints(pts);
  return cloud;
}

/// Collects ErrorEvent and WarningEvent messages (instead of printing them), like vtkTest::ErrorObserver.
class ErrorObserver : public vtkCommand
{
public:
  static ErrorObserver* New() { return new ErrorObserver; }
  vtkTypeMacro(ErrorObserver, vtkCommand);

  void Execute(vtkObject*, unsigned long event, void* callData) override
  {
    const std::string message = callData ? static_cast<const char*>(callData) : "";
    if (event == vtkCommand::ErrorEvent)
    {
      this->Errors.push_back(message);
    }
    else if (event == vtkCommand::WarningEvent)
    {
      this->Warnings.push_back(message);
    }
  }

  /// Observes errors and warnings of @p object.
  void Watch(vtkObject* object)
  {
    object->AddObserver(vtkCommand::ErrorEvent, this);
    object->AddObserver(vtkCommand::WarningEvent, this);
  }

  bool ErrorContains(const std::string& fragment) const { return Contains(this->Errors, fragment); }
  bool WarningContains(const std::string& fragment) const { return Contains(this->Warnings, fragment); }
  std::string AllErrors() const
  {
    std::string all;
    for (const auto& e : this->Errors)
    {
      all += e + "\n";
    }
    return all;
  }
  void Clear()
  {
    this->Errors.clear();
    this->Warnings.clear();
  }

  std::vector<std::string> Errors;
  std::vector<std::string> Warnings;

private:
  static bool Contains(const std::vector<std::string>& list, const std::string& fragment)
  {
    for (const auto& m : list)
    {
      if (m.find(fragment) != std::string::npos)
      {
        return true;
      }
    }
    return false;
  }
};

/// Number of non-finite values over every point- and cell-data array of @p ds.
inline long CountNonFinite(vtkDataSet* ds)
{
  long bad = 0;
  for (vtkDataSetAttributes* attributes :
    { static_cast<vtkDataSetAttributes*>(ds->GetPointData()), static_cast<vtkDataSetAttributes*>(ds->GetCellData()) })
  {
    for (int a = 0; a < attributes->GetNumberOfArrays(); ++a)
    {
      vtkDataArray* array = attributes->GetArray(a);
      if (!array)
      {
        continue;
      }
      for (vtkIdType t = 0; t < array->GetNumberOfTuples(); ++t)
      {
        for (int c = 0; c < array->GetNumberOfComponents(); ++c)
        {
          bad += std::isfinite(array->GetComponent(t, c)) ? 0 : 1;
        }
      }
    }
  }
  return bad;
}

} // namespace pss_field_test
