// SPDX-License-Identifier: BSD-3-Clause
// Who chooses vtkSMPTools' backend: the application, through
// vtkPointSetSurface::UseThreadedBackend(), never a filter's run.
#include "FilterTestUtilities.h"

#include "vtkPointSetSurface.h"
#include "vtkPointSetSurfaceMesher.h"
#include "vtkPointSetSurfaceProjection.h"
#include "vtkSMPTools.h"

#include <cstdlib>
#include <optional>

namespace
{

using pss_test::MakePoints;
using pss_test::Point;

// Restores the backend and the environment variable a test changed.
class BackendGuard
{
public:
  BackendGuard()
    : Backend(vtkSMPTools::GetBackend())
  {
    if (const char* v = std::getenv(Variable))
    {
      Environment = v;
    }
  }
  ~BackendGuard()
  {
    if (Environment)
    {
      setenv(Variable, Environment->c_str(), 1);
    }
    else
    {
      unsetenv(Variable);
    }
    vtkSMPTools::SetBackend(Backend.c_str());
  }
  static constexpr const char* Variable = "VTK_SMP_BACKEND_IN_USE";

private:
  std::string Backend;
  std::optional<std::string> Environment;
};

std::vector<Point> Circle(int n, double radius)
{
  std::vector<Point> points;
  for (int i = 0; i < n; ++i)
  {
    const double t = 2.0 * M_PI * i / n;
    points.push_back({ radius * std::cos(t), radius * std::sin(t), 0.0 });
  }
  return points;
}

} // namespace

TEST(Threading, FiltersLeaveTheApplicationsBackendAlone)
{
  BackendGuard guard;
  unsetenv(BackendGuard::Variable);
  vtkSMPTools::SetBackend("Sequential");
  auto cloud = MakePoints(Circle(200, 10.0));
  vtkNew<vtkPointSetSurfaceProjection> projection;
  projection->SetInputData(cloud);
  projection->Update();
  vtkNew<vtkPointSetSurfaceMesher> mesher;
  mesher->SetInputData(cloud);
  mesher->Update();
  ASSERT_EQ(projection->GetOutput()->GetNumberOfPoints(), 200);
  ASSERT_GT(mesher->GetOutput()->GetNumberOfCells(), 0);
  EXPECT_STREQ(vtkSMPTools::GetBackend(), "Sequential");
}

TEST(Threading, UseThreadedBackendSwitchesSequentialUnlessTheUserChose)
{
  BackendGuard guard;
  vtkSMPTools::SetBackend("Sequential");
  setenv(BackendGuard::Variable, "Sequential", 1);
  EXPECT_STREQ(vtkPointSetSurface::UseThreadedBackend(), "Sequential");
  unsetenv(BackendGuard::Variable);
  EXPECT_STREQ(vtkPointSetSurface::UseThreadedBackend(), "STDThread");
  EXPECT_STREQ(vtkSMPTools::GetBackend(), "STDThread");
}
