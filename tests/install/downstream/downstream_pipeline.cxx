// The installed VTK module in a pipeline: vtkPointSetSurfaceCloudSource (6,000 points on a sphere of
// radius 10, noise 0.3) -> vtkPointSetSurfaceProjection (centre of mass, h = 1). Every point must
// converge, and the projected cloud must sit less than half as far from the sphere as the noisy one.
#include "vtkPointSetSurface.h"
#include "vtkPointSetSurfaceCloudSource.h"
#include "vtkPointSetSurfaceProjection.h"

#include "pss/Core.h"

#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <cmath>
#include <cstdio>

namespace
{
double meanDistanceToSphere(vtkPolyData* cloud, double radius)
{
  double sum = 0.0;
  for (vtkIdType i = 0; i < cloud->GetNumberOfPoints(); ++i)
  {
    double p[3];
    cloud->GetPoint(i, p);
    sum += std::abs(std::sqrt(p[0] * p[0] + p[1] * p[1] + p[2] * p[2]) - radius);
  }
  return sum / static_cast<double>(cloud->GetNumberOfPoints());
}
}

int main()
{
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  source->SetSceneToSphere();
  source->SetSize(20.0);
  source->SetNumberOfPoints(6000);
  source->SetNoise(0.3);
  source->SetDimension(3);
  vtkNew<vtkPointSetSurfaceProjection> projection;
  projection->SetInputConnection(source->GetOutputPort());
  projection->GetSurface()->SetVariantToCenterOfMass();
  projection->GetSurface()->AutomaticScaleOff();
  projection->GetSurface()->SetScaleFactor(1.0);
  projection->Update();

  vtkPolyData* cloud = source->GetOutput();
  vtkPolyData* projected = projection->GetOutput();
  vtkDataArray* converged = projected->GetPointData()->GetArray("Converged");
  if (projected->GetNumberOfPoints() != cloud->GetNumberOfPoints() || !converged)
  {
    std::printf("expected %lld projected points with a Converged array\n",
      static_cast<long long>(cloud->GetNumberOfPoints()));
    return 1;
  }
  for (vtkIdType i = 0; i < converged->GetNumberOfTuples(); ++i)
  {
    if (converged->GetTuple1(i) != 1.0)
    {
      std::printf("point %lld did not converge\n", static_cast<long long>(i));
      return 1;
    }
  }
  const double before = meanDistanceToSphere(cloud, 10.0);
  const double after = meanDistanceToSphere(projected, 10.0);
  // The core is linked too: its default parameters are the filter's.
  const pss::SurfaceParameters defaults;
  std::printf("pipeline: %lld points, mean distance to the sphere %.4f -> %.4f (kernel cutoff %g h)\n",
    static_cast<long long>(projected->GetNumberOfPoints()), before, after, defaults.cutoff);
  return after < 0.5 * before ? 0 : 1;
}
