// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPointSetSurfaceImplicitFunction.h"

#include "PointSetSurfacesFieldEvaluation.h"
#include "PointSetSurfacesVTKUtilities.h"
#include "vtkPointSetSurface.h"

#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPointSet.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"

#include "pss/PointIndex.h"
#include "pss/SurfaceDefinition.h"
#include "pss/Workspace.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <mutex>
#include <string>
#include <vector>

vtkStandardNewMacro(vtkPointSetSurfaceImplicitFunction);
vtkCxxSetObjectMacro(vtkPointSetSurfaceImplicitFunction, Surface, vtkPointSetSurface);

// The prepared state. Written only under Mutex; published to lock-free readers by the release
// store of ReadyStamp (the MTime it was prepared for), which readers load with acquire.
struct vtkPointSetSurfaceImplicitFunction::Internals
{
  std::mutex Mutex;
  std::atomic<vtkMTimeType> ReadyStamp{ 0 };
  std::unique_ptr<pss_vtk::FieldEvaluator> Evaluator; // null when the last preparation failed
  double H = 0.0;
  int Dimension = 3;

  // Any thread of the host may evaluate: each evaluation borrows an idle workspace (or makes
  // one) and gives it back, so consecutive samples reuse its cached neighbours.
  std::mutex IdleMutex;
  std::vector<std::unique_ptr<pss::Workspace>> Idle;

  std::unique_ptr<pss::Workspace> Borrow()
  {
    std::lock_guard<std::mutex> lock(this->IdleMutex);
    if (this->Idle.empty())
    {
      return std::make_unique<pss::Workspace>();
    }
    std::unique_ptr<pss::Workspace> ws = std::move(this->Idle.back());
    this->Idle.pop_back();
    return ws;
  }

  void GiveBack(std::unique_ptr<pss::Workspace> ws)
  {
    std::lock_guard<std::mutex> lock(this->IdleMutex);
    this->Idle.push_back(std::move(ws));
  }
};

vtkPointSetSurfaceImplicitFunction::vtkPointSetSurfaceImplicitFunction()
  : State(new Internals)
{
  this->Surface = vtkPointSetSurface::New();
}

vtkPointSetSurfaceImplicitFunction::~vtkPointSetSurfaceImplicitFunction()
{
  this->State->Evaluator.reset(); // before the surface it refers to goes
  this->SetSurface(nullptr);
  this->SetInputData(nullptr);
}

void vtkPointSetSurfaceImplicitFunction::SetInputData(vtkPointSet* cloud)
{
  if (cloud == this->Input)
  {
    return;
  }
  vtkPointSet* previous = this->Input;
  this->Input = cloud;
  if (cloud)
  {
    cloud->Register(this);
  }
  if (previous)
  {
    previous->UnRegister(this);
  }
  this->Modified();
}

void vtkPointSetSurfaceImplicitFunction::SetPoints(vtkPoints* points)
{
  if (!points)
  {
    this->SetInputData(nullptr);
    return;
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  this->SetInputData(cloud);
}

vtkMTimeType vtkPointSetSurfaceImplicitFunction::GetMTime()
{
  vtkMTimeType t = pss_vtk::LatestMTime(this->Superclass::GetMTime(), this->Surface);
  t = pss_vtk::LatestMTime(t, this->Input);
  return pss_vtk::LatestMTime(t, this->Input ? this->Input->GetPoints() : nullptr);
}

bool vtkPointSetSurfaceImplicitFunction::IsReady(bool acquire)
{
  const vtkMTimeType stamp = this->GetMTime();
  if (this->State->ReadyStamp.load(acquire ? std::memory_order_acquire : std::memory_order_relaxed) != stamp)
  {
    return false;
  }
  // A vtkPointSetSurface caches one cloud: if an object sharing it prepared it for another cloud
  // since, its definition is no longer the one evaluated here.
  const pss_vtk::FieldEvaluator* evaluator = this->State->Evaluator.get();
  return !evaluator || (this->Surface && &evaluator->Surface() == this->Surface->GetDefinition());
}

bool vtkPointSetSurfaceImplicitFunction::Initialize()
{
  std::lock_guard<std::mutex> lock(this->State->Mutex);
  if (this->IsReady(false))
  {
    return this->State->Evaluator != nullptr;
  }
  const vtkMTimeType stamp = this->GetMTime();
  Internals& s = *this->State;
  s.Evaluator.reset();
  s.H = 0.0;
  bool ok = false;
  if (!this->Surface)
  {
    vtkErrorMacro(<< "no vtkPointSetSurface is set");
  }
  else if (!this->Input)
  {
    vtkErrorMacro(<< "no point cloud: call SetInputData() or SetPoints()");
  }
  else if (!this->Surface->Prepare(this->Input))
  {
    vtkErrorMacro(<< "cannot define the surface: " << this->Surface->GetLastError());
  }
  else
  {
    pss::Orientation orientation;
    std::string error;
    if (!pss_vtk::MakeOrientation(this->OrientationMode, this->ReferencePoint, this->ReferenceDirection,
          this->Surface->GetIndex()->centroid(), orientation, error))
    {
      vtkErrorMacro(<< error);
    }
    else
    {
      try
      {
        s.Evaluator = std::make_unique<pss_vtk::FieldEvaluator>(*this->Surface->GetDefinition(), orientation);
        s.H = this->Surface->GetEffectiveScale();
        s.Dimension = this->Surface->GetEffectiveDimension();
        ok = true;
      }
      catch (const std::exception& e)
      {
        vtkErrorMacro(<< "cannot define the surface: " << e.what());
      }
    }
  }
  // Also after a failure: report it once per modification, not once per sample.
  s.ReadyStamp.store(stamp, std::memory_order_release);
  return ok;
}

double vtkPointSetSurfaceImplicitFunction::EvaluateFunction(double x[3])
{
  if (!this->IsReady(true))
  {
    this->Initialize();
  }
  const pss_vtk::FieldEvaluator* evaluator = this->State->Evaluator.get();
  if (!evaluator)
  {
    return 0.0;
  }
  std::unique_ptr<pss::Workspace> ws = this->State->Borrow();
  double value = 0.0;
  switch (this->OutputQuantity)
  {
    case DELTA:
      value = evaluator->Evaluate(x, *ws, pss_vtk::FIELD_DELTA).delta;
      break;
    case ENERGY:
      value = evaluator->Evaluate(x, *ws, pss_vtk::FIELD_DIRECTIONAL).energy;
      break;
    default:
      value = evaluator->Evaluate(x, *ws, pss_vtk::FIELD_DIRECTIONAL).g;
  }
  this->State->GiveBack(std::move(ws));
  return value;
}

void vtkPointSetSurfaceImplicitFunction::EvaluateGradient(double x[3], double g[3])
{
  g[0] = g[1] = g[2] = 0.0;
  if (!this->IsReady(true))
  {
    this->Initialize();
  }
  if (!this->State->Evaluator || !std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
  {
    return;
  }
  const double step = this->FiniteDifferenceStep * this->State->H;
  const int axes = this->State->Dimension == 2 ? 2 : 3; // a 2D cloud ignores z
  for (int a = 0; a < axes; ++a)
  {
    double plus[3] = { x[0], x[1], x[2] };
    double minus[3] = { x[0], x[1], x[2] };
    plus[a] += step;
    minus[a] -= step;
    g[a] = (this->EvaluateFunction(plus) - this->EvaluateFunction(minus)) / (plus[a] - minus[a]);
  }
}

double vtkPointSetSurfaceImplicitFunction::GetEffectiveScale()
{
  if (!this->IsReady(true))
  {
    this->Initialize();
  }
  return this->State->H;
}

void vtkPointSetSurfaceImplicitFunction::PrintSelf(ostream& os, vtkIndent indent)
{
  static const char* const quantities[] = { "ImplicitG", "Energy", "Delta" };
  static const char* const modes[] = { "AwayFromCentroid", "AwayFromPoint", "AlongDirection" };
  this->Superclass::PrintSelf(os, indent);
  os << indent << "OutputQuantity: " << quantities[this->OutputQuantity] << "\n";
  os << indent << "OrientationMode: " << modes[this->OrientationMode] << "\n";
  os << indent << "ReferencePoint: (" << this->ReferencePoint[0] << ", " << this->ReferencePoint[1] << ", "
     << this->ReferencePoint[2] << ")\n";
  os << indent << "ReferenceDirection: (" << this->ReferenceDirection[0] << ", " << this->ReferenceDirection[1]
     << ", " << this->ReferenceDirection[2] << ")\n";
  os << indent << "FiniteDifferenceStep: " << this->FiniteDifferenceStep << "\n";
  os << indent << "Input: " << static_cast<void*>(this->Input) << "\n";
  pss_vtk::PrintSurface(os, indent, this->Surface);
}
