// SPDX-License-Identifier: BSD-3-Clause
#include "PaperFields.h"

#include "vtkContourFilter.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkImageData.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStaticPointLocator.h"
#include "vtkStreamTracer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace pss_paper
{

/// Streamlines of the sampled n, seeded on a lattice of spacing @p seedSpacingInH, both ways.
vtkSmartPointer<vtkPolyData> Streamlines(vtkImageData* field, const Scene& scene, double seedSpacingInH,
  double lengthInH)
{
  double bounds[6];
  field->GetBounds(bounds);
  const double step = seedSpacingInH * scene.h;
  std::vector<pss::Vec3> seeds;
  for (double y = bounds[2] + 0.5 * step; y < bounds[3]; y += step)
  {
    for (double x = bounds[0] + 0.5 * step; x < bounds[1]; x += step)
    {
      seeds.emplace_back(x, y, 0.0);
    }
  }
  vtkNew<vtkStreamTracer> tracer;
  tracer->SetInputData(field);
  tracer->SetSourceData(MakePointCloud(seeds));
  tracer->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, "Normal");
  tracer->SetIntegratorTypeToRungeKutta4();
  tracer->SetIntegrationStepUnit(vtkStreamTracer::CELL_LENGTH_UNIT);
  tracer->SetInitialIntegrationStep(0.25);
  tracer->SetMaximumPropagation(lengthInH * scene.h);
  tracer->SetMaximumNumberOfSteps(5000);
  tracer->SetIntegrationDirectionToBoth();
  tracer->SetComputeVorticity(false);
  tracer->Update();
  auto lines = vtkSmartPointer<vtkPolyData>::New();
  lines->DeepCopy(tracer->GetOutput());
  return lines;
}

/// Iso-contours of @p array at @p values (vtkContourFilter; the contour value is kept as scalars).
vtkSmartPointer<vtkPolyData> Contours(vtkImageData* field, const char* array, const std::vector<double>& values)
{
  vtkNew<vtkContourFilter> contour;
  contour->SetInputData(field);
  contour->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, array);
  contour->SetNumberOfContours(static_cast<int>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    contour->SetValue(static_cast<int>(i), values[i]);
  }
  contour->ComputeScalarsOn();
  contour->Update();
  auto lines = vtkSmartPointer<vtkPolyData>::New();
  lines->DeepCopy(contour->GetOutput());
  return lines;
}

/// @p count iso-values of `LogEnergy` evenly spaced between its 2nd and 98th percentiles.
vtkSmartPointer<vtkPolyData> EnergyContours(vtkImageData* field, int count)
{
  vtkDataArray* a = field->GetPointData()->GetArray("LogEnergy");
  std::vector<double> v(static_cast<std::size_t>(a->GetNumberOfTuples()));
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    v[static_cast<std::size_t>(i)] = a->GetTuple1(i);
  }
  const double lo = Percentile(v, 0.02);
  const double hi = Percentile(v, 0.98);
  std::vector<double> values;
  for (int k = 0; k < count; ++k)
  {
    values.push_back(lo + (hi - lo) * (k + 0.5) / count);
  }
  return Contours(field, "LogEnergy", values);
}

/**
 * Near-singular points of n: grid samples whose `Stability` is a strict minimum of its 3 x 3
 * neighbourhood and below @p threshold (n is undefined where the stability is 0).
 */
vtkSmartPointer<vtkPolyData> NearSingularPoints(vtkImageData* field, double threshold)
{
  int dims[3];
  field->GetDimensions(dims);
  vtkDataArray* stability = field->GetPointData()->GetArray("Stability");
  auto at = [&](int i, int j) { return stability->GetTuple1(static_cast<vtkIdType>(j) * dims[0] + i); };
  std::vector<pss::Vec3> points;
  std::vector<double> values;
  for (int j = 1; j + 1 < dims[1]; ++j)
  {
    for (int i = 1; i + 1 < dims[0]; ++i)
    {
      const double s = at(i, j);
      if (!(s < threshold))
      {
        continue;
      }
      bool minimum = true;
      for (int dj = -1; dj <= 1 && minimum; ++dj)
      {
        for (int di = -1; di <= 1; ++di)
        {
          if ((di != 0 || dj != 0) && at(i + di, j + dj) <= s)
          {
            minimum = false;
            break;
          }
        }
      }
      if (minimum)
      {
        double p[3];
        field->GetPoint(static_cast<vtkIdType>(j) * dims[0] + i, p);
        points.emplace_back(p[0], p[1], p[2]);
        values.push_back(s);
      }
    }
  }
  vtkSmartPointer<vtkPolyData> out = MakePointCloud(points);
  vtkNew<vtkDoubleArray> s;
  s->SetName("Stability");
  for (double v : values)
  {
    s->InsertNextValue(v);
  }
  out->GetPointData()->AddArray(s);
  return out;
}


DeltaStats MeasureDelta(vtkImageData* field, const Scene& scene)
{
  vtkNew<vtkStaticPointLocator> locator;
  locator->SetDataSet(scene.cloud);
  locator->BuildLocator();
  vtkDataArray* delta = field->GetPointData()->GetArray("Delta");
  int dims[3];
  field->GetDimensions(dims);
  DeltaStats st;
  st.samples = field->GetNumberOfPoints();
  std::vector<double> d2(static_cast<std::size_t>(st.samples));
  for (vtkIdType i = 0; i < st.samples; ++i)
  {
    double x[3];
    field->GetPoint(i, x);
    double q[3];
    scene.cloud->GetPoint(locator->FindClosestPoint(x), q);
    d2[static_cast<std::size_t>(i)] = vtkMath::Distance2BetweenPoints(x, q);
    const double v = delta->GetTuple1(i);
    // delta is a weighted mean of squared distances: never below the smallest one (to rounding).
    st.aboveSquaredDistance += v >= d2[static_cast<std::size_t>(i)] * (1.0 - 1e-12) ? 1 : 0;
    if (d2[static_cast<std::size_t>(i)] >= std::pow(2.5 * scene.h, 2))
    {
      st.farRatioMin = std::min(st.farRatioMin, v / d2[static_cast<std::size_t>(i)]);
      st.farRatioMax = std::max(st.farRatioMax, v / d2[static_cast<std::size_t>(i)]);
    }
  }
  for (int j = 1; j + 1 < dims[1]; ++j)
  {
    for (int i = 1; i + 1 < dims[0]; ++i)
    {
      const vtkIdType id = static_cast<vtkIdType>(j) * dims[0] + i;
      const double v = delta->GetTuple1(id);
      bool minimum = true;
      for (int dj = -1; dj <= 1 && minimum; ++dj)
      {
        for (int di = -1; di <= 1; ++di)
        {
          if ((di || dj) && delta->GetTuple1(id + static_cast<vtkIdType>(dj) * dims[0] + di) <= v)
          {
            minimum = false;
            break;
          }
        }
      }
      if (minimum)
      {
        ++st.minima;
        st.minimaMaxDistance = std::max(st.minimaMaxDistance, std::sqrt(d2[static_cast<std::size_t>(id)]) / scene.h);
      }
    }
  }
  return st;
}

/// The converged end points of @p projection whose `ExtremumType` is @p type (1 min, 2 max).
vtkSmartPointer<vtkPolyData> Extrema(vtkPolyData* projection, int type)
{
  vtkDataArray* converged = projection->GetPointData()->GetArray("Converged");
  vtkDataArray* extremum = projection->GetPointData()->GetArray("ExtremumType");
  std::vector<pss::Vec3> points;
  for (vtkIdType i = 0; i < projection->GetNumberOfPoints(); ++i)
  {
    if (converged->GetTuple1(i) != 0.0 && static_cast<int>(extremum->GetTuple1(i)) == type)
    {
      double p[3];
      projection->GetPoint(i, p);
      points.emplace_back(p[0], p[1], p[2]);
    }
  }
  return MakePointCloud(points);
}

vtkSmartPointer<vtkPolyData> DomainAtStarts(vtkPolyData* starts, vtkPolyData* projection)
{
  vtkDataArray* label = projection->GetPointData()->GetArray("DomainLabel");
  if (!label || projection->GetNumberOfPoints() != starts->GetNumberOfPoints())
  {
    throw std::runtime_error("the classifier's output has no DomainLabel per start point");
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->ShallowCopy(starts);
  out->GetPointData()->Initialize();
  out->GetPointData()->AddArray(label);
  return out;
}

} // namespace pss_paper
