// SPDX-License-Identifier: BSD-3-Clause
/**
 * Determinism of every filter: the same input gives bitwise-identical outputs across runs and
 * across 1 and 2 threads (vtkSMPTools' STDThread backend). Each case builds a fresh pipeline three
 * times, on 1, 2 and again 2 threads, and compares every output port byte by byte: the points,
 * every point, cell and field data array, the cells, and an image's geometry.
 *
 * Why it holds: every point is computed on its own, and the core gathers each neighbourhood in
 * index order from absolute coordinates, so no sum depends on which thread ran the point, on the
 * chunking, or on what that thread's candidate cache held before (Kernel.h). Reductions (the
 * glyphs' global scale, the sampler's PROPAGATE tree) run after the parallel loop, in index order.
 * The same tests run under ThreadSanitizer (ctest -R Sanitizers.Thread).
 */
#include "vtkPointSetSurface.h"
#include "vtkPointSetSurfaceCloudSource.h"
#include "vtkPointSetSurfaceDomainClassifier.h"
#include "vtkPointSetSurfaceEnergyGlyphs.h"
#include "vtkPointSetSurfaceFieldSampler.h"
#include "vtkPointSetSurfaceImplicitFunction.h"
#include "vtkPointSetSurfaceProjection.h"

#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSampleFunction.h"
#include "vtkSmartPointer.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <cstring>
#include <functional>
#include <limits>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

namespace
{

// Byte-for-byte equality of two arrays (type, shape and contents), naming the first difference.
void ExpectSameBits(vtkDataArray* a, vtkDataArray* b, const std::string& what)
{
  ASSERT_EQ(a == nullptr, b == nullptr) << what;
  if (!a)
  {
    return;
  }
  ASSERT_EQ(a->GetDataType(), b->GetDataType()) << what;
  ASSERT_EQ(a->GetNumberOfComponents(), b->GetNumberOfComponents()) << what;
  ASSERT_EQ(a->GetNumberOfTuples(), b->GetNumberOfTuples()) << what;
  const std::size_t size = static_cast<std::size_t>(a->GetDataTypeSize());
  const vtkIdType values = a->GetNumberOfValues();
  const auto* pa = static_cast<const unsigned char*>(a->GetVoidPointer(0));
  const auto* pb = static_cast<const unsigned char*>(b->GetVoidPointer(0));
  if (values == 0 || std::memcmp(pa, pb, size * static_cast<std::size_t>(values)) == 0)
  {
    return;
  }
  for (vtkIdType v = 0; v < values; ++v)
  {
    if (std::memcmp(pa + size * v, pb + size * v, size) != 0)
    {
      const int nc = a->GetNumberOfComponents();
      ADD_FAILURE() << what << ": first difference at tuple " << v / nc << ", component " << v % nc << ": "
                    << a->GetComponent(v / nc, static_cast<int>(v % nc)) << " vs "
                    << b->GetComponent(v / nc, static_cast<int>(v % nc));
      return;
    }
  }
}

void ExpectSameArrays(vtkFieldData* a, vtkFieldData* b, const std::string& what)
{
  ASSERT_EQ(a->GetNumberOfArrays(), b->GetNumberOfArrays()) << what;
  for (int i = 0; i < a->GetNumberOfArrays(); ++i)
  {
    vtkAbstractArray* x = a->GetAbstractArray(i);
    vtkAbstractArray* y = b->GetAbstractArray(i);
    ASSERT_STREQ(x->GetName(), y->GetName()) << what;
    ExpectSameBits(vtkDataArray::SafeDownCast(x), vtkDataArray::SafeDownCast(y), what + " array " + x->GetName());
  }
}

void ExpectSameCells(vtkCellArray* a, vtkCellArray* b, const std::string& what)
{
  ExpectSameBits(a->GetOffsetsArray(), b->GetOffsetsArray(), what + " offsets");
  ExpectSameBits(a->GetConnectivityArray(), b->GetConnectivityArray(), what + " connectivity");
}

// Every byte a downstream filter could see.
void ExpectSameOutput(vtkDataObject* a, vtkDataObject* b, const std::string& what)
{
  ASSERT_TRUE(a && b) << what;
  ASSERT_STREQ(a->GetClassName(), b->GetClassName()) << what;
  auto* da = vtkDataSet::SafeDownCast(a);
  auto* db = vtkDataSet::SafeDownCast(b);
  ASSERT_TRUE(da && db) << what;
  ASSERT_EQ(da->GetNumberOfPoints(), db->GetNumberOfPoints()) << what;
  ASSERT_EQ(da->GetNumberOfCells(), db->GetNumberOfCells()) << what;
  if (auto* pa = vtkPointSet::SafeDownCast(a))
  {
    auto* pb = vtkPointSet::SafeDownCast(b);
    ASSERT_EQ(pa->GetPoints() == nullptr, pb->GetPoints() == nullptr) << what;
    if (pa->GetPoints())
    {
      ExpectSameBits(pa->GetPoints()->GetData(), pb->GetPoints()->GetData(), what + " points");
    }
  }
  if (auto* ia = vtkImageData::SafeDownCast(a))
  {
    auto* ib = vtkImageData::SafeDownCast(b);
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_EQ(ia->GetExtent()[2 * k], ib->GetExtent()[2 * k]) << what;
      EXPECT_EQ(ia->GetExtent()[2 * k + 1], ib->GetExtent()[2 * k + 1]) << what;
      EXPECT_EQ(std::memcmp(&ia->GetOrigin()[k], &ib->GetOrigin()[k], sizeof(double)), 0) << what << " origin";
      EXPECT_EQ(std::memcmp(&ia->GetSpacing()[k], &ib->GetSpacing()[k], sizeof(double)), 0) << what << " spacing";
    }
  }
  if (auto* pa = vtkPolyData::SafeDownCast(a))
  {
    auto* pb = vtkPolyData::SafeDownCast(b);
    ExpectSameCells(pa->GetVerts(), pb->GetVerts(), what + " verts");
    ExpectSameCells(pa->GetLines(), pb->GetLines(), what + " lines");
    ExpectSameCells(pa->GetPolys(), pb->GetPolys(), what + " polys");
    ExpectSameCells(pa->GetStrips(), pb->GetStrips(), what + " strips");
  }
  ExpectSameArrays(da->GetPointData(), db->GetPointData(), what + " point data");
  ExpectSameArrays(da->GetCellData(), db->GetCellData(), what + " cell data");
  ExpectSameArrays(a->GetFieldData(), b->GetFieldData(), what + " field data");
}

/// Uses the STDThread backend with @p threads threads; false when the machine cannot give them.
bool UseThreads(int threads)
{
  vtkSMPTools::SetBackend("STDThread");
  vtkSMPTools::Initialize(threads);
  return vtkSMPTools::GetEstimatedNumberOfThreads() == threads;
}

/// A pipeline run: builds everything anew and returns deep copies of the outputs that matter.
using Run = std::function<std::vector<vtkSmartPointer<vtkDataObject>>()>;

vtkSmartPointer<vtkDataObject> Copy(vtkDataObject* output)
{
  vtkSmartPointer<vtkDataObject> copy = vtkSmartPointer<vtkDataObject>::Take(output->NewInstance());
  copy->DeepCopy(output);
  return copy;
}

/// Runs @p run on 1, 2 and again 2 threads and compares every output with the first run's.
void ExpectDeterministic(const std::string& name, const Run& run, vtkIdType minimumPoints = 1)
{
  if (std::thread::hardware_concurrency() < 2)
  {
    GTEST_SKIP() << "this machine has a single hardware thread";
  }
  std::vector<std::vector<vtkSmartPointer<vtkDataObject>>> outputs;
  const auto start = std::chrono::steady_clock::now();
  for (const int threads : { 1, 2, 2 })
  {
    ASSERT_TRUE(UseThreads(threads)) << "vtkSMPTools did not give " << threads << " thread(s)";
    outputs.push_back(run());
  }
  vtkSMPTools::Initialize(0);
  std::cout << "[ determinism ] " << name << ": 3 runs in "
            << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s\n";
  ASSERT_FALSE(outputs[0].empty());
  // A determinism test on an empty output would prove nothing.
  auto* first = vtkDataSet::SafeDownCast(outputs[0][0]);
  ASSERT_NE(first, nullptr);
  EXPECT_GE(first->GetNumberOfPoints(), minimumPoints) << name;
  for (std::size_t r = 1; r < outputs.size(); ++r)
  {
    ASSERT_EQ(outputs[r].size(), outputs[0].size());
    for (std::size_t port = 0; port < outputs[0].size(); ++port)
    {
      std::ostringstream what;
      what << name << ", output " << port << ", run " << r << " (" << (r == 0 ? 1 : 2) << " threads) vs run 0 (1 thread)";
      ExpectSameOutput(outputs[0][port], outputs[r][port], what.str());
    }
  }
}

/// The test cloud: a noisy open curve (2D, Figure 1) or a noisy sphere (3D).
vtkSmartPointer<vtkPolyData> Cloud(int scene, vtkIdType count, double noise, int dimension)
{
  vtkNew<vtkPointSetSurfaceCloudSource> source;
  source->SetScene(scene);
  source->SetNumberOfPoints(count);
  source->SetSize(100.0);
  source->SetNoise(noise);
  source->SetDimension(dimension);
  source->SetSeed(7);
  source->Update();
  return source->GetOutput();
}

vtkSmartPointer<vtkPolyData> NoisyCurve()
{
  return Cloud(vtkPointSetSurfaceCloudSource::NOISY_CURVE, 300, 4.0, 2);
}

vtkSmartPointer<vtkPolyData> NoisySphere()
{
  return Cloud(vtkPointSetSurfaceCloudSource::SPHERE, 400, 1.0, 3);
}

/// A lattice of start points around the curve, some far from it (outside every domain).
vtkSmartPointer<vtkPolyData> Starts2D(int n)
{
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (int i = 0; i < n; ++i)
  {
    for (int j = 0; j < n; ++j)
    {
      points->InsertNextPoint(-10.0 + 120.0 * i / (n - 1), -40.0 + 80.0 * j / (n - 1), 0.0);
    }
  }
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->SetPoints(points);
  return out;
}

const int kVariants[] = { vtkPointSetSurface::LEVIN_MLS, vtkPointSetSurface::NORMALIZED_MLS,
  vtkPointSetSurface::CENTER_OF_MASS, vtkPointSetSurface::INTEGRAL, vtkPointSetSurface::DELTA };

const char* VariantName(int v)
{
  static const char* const names[] = { "LevinMLS", "NormalizedMLS", "CenterOfMass", "Integral", "Delta" };
  return names[v];
}

} // namespace

TEST(FilterDeterminism, CloudSource)
{
  for (const int scene : { vtkPointSetSurfaceCloudSource::NOISY_CURVE, vtkPointSetSurfaceCloudSource::SPHERE })
  {
    ExpectDeterministic(std::string("cloud source scene ") + std::to_string(scene), [scene]() {
      vtkNew<vtkPointSetSurfaceCloudSource> source;
      source->SetScene(scene);
      source->SetNumberOfPoints(5000);
      source->SetNoise(2.0);
      source->SetDimension(3);
      source->Update();
      return std::vector<vtkSmartPointer<vtkDataObject>>{ Copy(source->GetOutput()) };
    }, 5000);
  }
}

// Every variant, both procedures, seeking minima and maxima, with the projection lines: the curve
// projects itself (2D); around the sphere, 24 noisier start points (n_I in 3D is a search over
// the sphere of directions at every step: a few seconds per hundred points).
TEST(FilterDeterminism, Projection)
{
  vtkSmartPointer<vtkPolyData> curve = NoisyCurve();
  vtkSmartPointer<vtkPolyData> sphere = NoisySphere();
  vtkSmartPointer<vtkPolyData> sphereStarts = Cloud(vtkPointSetSurfaceCloudSource::SPHERE, 24, 6.0, 3);
  for (const int variant : kVariants)
  {
    for (const int procedure : { vtkPointSetSurfaceProjection::EXTREMAL, vtkPointSetSurfaceProjection::PLANE })
    {
      for (const bool threeD : { false, true })
      {
        // The integral variants' n_I in 3D is a search over the sphere: one procedure is enough there.
        if (threeD && variant >= vtkPointSetSurface::INTEGRAL && procedure == vtkPointSetSurfaceProjection::PLANE)
        {
          continue;
        }
        std::ostringstream name;
        name << "projection " << VariantName(variant) << (procedure ? " plane " : " extremal ") << (threeD ? "3D" : "2D");
        vtkPolyData* cloud = threeD ? sphere.Get() : curve.Get();
        vtkPolyData* starts = threeD ? sphereStarts.Get() : curve.Get();
        ExpectDeterministic(name.str(), [&]() {
          vtkNew<vtkPointSetSurfaceProjection> projection;
          projection->SetInputData(cloud);
          projection->SetStartPointsData(starts);
          projection->GetSurface()->SetVariant(variant);
          projection->SetProcedure(procedure);
          projection->SetSeekMaxima(variant == vtkPointSetSurface::LEVIN_MLS && !threeD);
          projection->GenerateProjectionLinesOn();
          projection->SetMaxIterations(threeD ? 20 : 100);
          projection->Update();
          return std::vector<vtkSmartPointer<vtkDataObject>>{ Copy(projection->GetOutput(0)),
            Copy(projection->GetOutput(1)) };
        }, starts->GetNumberOfPoints());
      }
    }
  }
}

// The cloud's own points are visited in the index's leaf order, their coordinates read from the
// index, other start points in Morton order from their array (vtkPointSetSurfaceProjection::
// RequestData): neither the order nor where a start is read must change a single bit. A NaN point
// exercises the skipped points, which come last in the first order and are read from the array.
TEST(FilterDeterminism, ProjectionIndependentOfVisitingOrder)
{
  vtkSmartPointer<vtkPolyData> cloud = NoisySphere();
  cloud->GetPoints()->SetPoint(17, std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0);
  vtkNew<vtkPolyData> sameStarts;
  sameStarts->DeepCopy(cloud);
  std::vector<vtkSmartPointer<vtkDataObject>> outputs;
  for (vtkPolyData* starts : { cloud.Get(), static_cast<vtkPolyData*>(sameStarts) })
  {
    vtkNew<vtkPointSetSurfaceDomainClassifier> classifier;
    classifier->SetInputData(cloud);
    classifier->SetStartPointsData(starts);
    classifier->GetSurface()->SetVariant(vtkPointSetSurface::CENTER_OF_MASS);
    classifier->GenerateProjectionLinesOn();
    classifier->Update();
    outputs.push_back(Copy(classifier->GetOutput(0)));
    outputs.push_back(Copy(classifier->GetOutput(1)));
  }
  ASSERT_EQ(vtkPolyData::SafeDownCast(outputs[0])->GetNumberOfPoints(), cloud->GetNumberOfPoints());
  ExpectSameOutput(outputs[0], outputs[2], "projected points, starts = cloud vs a copy of it");
  ExpectSameOutput(outputs[1], outputs[3], "projection lines, starts = cloud vs a copy of it");
}

TEST(FilterDeterminism, DomainClassifier)
{
  vtkSmartPointer<vtkPolyData> curve = NoisyCurve();
  vtkSmartPointer<vtkPolyData> starts = Starts2D(15);
  for (const int variant : kVariants)
  {
    ExpectDeterministic(std::string("classifier ") + VariantName(variant), [&]() {
      vtkNew<vtkPointSetSurfaceDomainClassifier> classifier;
      classifier->SetInputData(curve);
      classifier->SetStartPointsData(starts);
      classifier->GetSurface()->SetVariant(variant);
      classifier->GenerateProjectionLinesOn();
      classifier->Update();
      return std::vector<vtkSmartPointer<vtkDataObject>>{ Copy(classifier->GetOutput(0)),
        Copy(classifier->GetOutput(1)) };
    }, starts->GetNumberOfPoints());
  }
}

// Generated grids (every orientation mode, PROPAGATE included, and the domain labels) and a probe
// dataset.
TEST(FilterDeterminism, FieldSampler)
{
  vtkSmartPointer<vtkPolyData> curve = NoisyCurve();
  struct Case
  {
    int variant;
    int orientation;
    bool labels;
  };
  const Case cases[] = { { vtkPointSetSurface::LEVIN_MLS, vtkPointSetSurfaceFieldSampler::PROPAGATE, true },
    { vtkPointSetSurface::NORMALIZED_MLS, vtkPointSetSurfaceFieldSampler::AWAY_FROM_POINT, false },
    { vtkPointSetSurface::CENTER_OF_MASS, vtkPointSetSurfaceFieldSampler::AWAY_FROM_CENTROID, true },
    { vtkPointSetSurface::INTEGRAL, vtkPointSetSurfaceFieldSampler::PROPAGATE, false },
    { vtkPointSetSurface::DELTA, vtkPointSetSurfaceFieldSampler::ALONG_DIRECTION, false } };
  for (const Case& c : cases)
  {
    std::ostringstream name;
    name << "field sampler grid " << VariantName(c.variant) << " orientation " << c.orientation
         << (c.labels ? " with labels" : "");
    ExpectDeterministic(name.str(), [&]() {
      vtkNew<vtkPointSetSurfaceFieldSampler> sampler;
      sampler->SetSourceData(curve);
      sampler->GetSurface()->SetVariant(c.variant);
      sampler->SetOrientationMode(c.orientation);
      sampler->SetReferencePoint(50.0, -30.0, 0.0);
      sampler->SetReferenceDirection(0.0, 1.0, 0.0);
      sampler->GenerateSamplingGridOn();
      sampler->SetSampleDimensions(c.labels ? 21 : 41, c.labels ? 21 : 41, 1);
      sampler->SetComputeDomainLabels(c.labels);
      sampler->Update();
      return std::vector<vtkSmartPointer<vtkDataObject>>{ Copy(sampler->GetOutput()) };
    }, c.labels ? 441 : 1681);
  }
  vtkSmartPointer<vtkPolyData> probe = Starts2D(20);
  ExpectDeterministic("field sampler probe", [&]() {
    vtkNew<vtkPointSetSurfaceFieldSampler> sampler;
    sampler->SetSourceData(curve);
    sampler->SetInputData(probe);
    sampler->GetSurface()->SetVariantToCenterOfMass();
    sampler->Update();
    return std::vector<vtkSmartPointer<vtkDataObject>>{ Copy(sampler->GetOutput()) };
  }, probe->GetNumberOfPoints());
}

// The global scale is a maximum over all samples: the reduction must not depend on the threads.
TEST(FilterDeterminism, EnergyGlyphs)
{
  vtkSmartPointer<vtkPolyData> curve = NoisyCurve();
  vtkSmartPointer<vtkPolyData> sphere = NoisySphere();
  for (const int variant : kVariants)
  {
    for (const bool threeD : { false, true })
    {
      std::ostringstream name;
      name << "energy glyphs " << VariantName(variant) << (threeD ? " 3D" : " 2D");
      ExpectDeterministic(name.str(), [&]() {
        vtkNew<vtkPointSetSurfaceEnergyGlyphs> glyphs;
        glyphs->SetInputData(threeD ? sphere : curve);
        glyphs->SetSamplePointsData(threeD ? Cloud(vtkPointSetSurfaceCloudSource::SPHERE, 12, 8.0, 3) : Starts2D(8));
        glyphs->GetSurface()->SetVariant(variant);
        glyphs->SetResolution(threeD ? 12 : 36);
        glyphs->Update();
        return std::vector<vtkSmartPointer<vtkDataObject>>{ Copy(glyphs->GetOutput(0)), Copy(glyphs->GetOutput(1)) };
      });
    }
  }
}

// vtkSampleFunction evaluates the implicit function from its own vtkSMPTools threads.
TEST(FilterDeterminism, ImplicitFunctionThroughSampleFunction)
{
  vtkSmartPointer<vtkPolyData> curve = NoisyCurve();
  for (const int variant : kVariants)
  {
    for (const int quantity : { vtkPointSetSurfaceImplicitFunction::IMPLICIT_G,
           vtkPointSetSurfaceImplicitFunction::ENERGY, vtkPointSetSurfaceImplicitFunction::DELTA })
    {
      std::ostringstream name;
      name << "implicit function " << VariantName(variant) << " quantity " << quantity;
      ExpectDeterministic(name.str(), [&]() {
        vtkNew<vtkPointSetSurfaceImplicitFunction> function;
        function->SetInputData(curve);
        function->GetSurface()->SetVariant(variant);
        function->SetOutputQuantity(quantity);
        vtkNew<vtkSampleFunction> sample;
        sample->SetImplicitFunction(function);
        sample->SetModelBounds(-10.0, 110.0, -40.0, 40.0, 0.0, 0.0);
        sample->SetSampleDimensions(25, 17, 1);
        sample->SetOutputScalarTypeToDouble();
        sample->ComputeNormalsOn(); // the gradient too
        sample->Update();
        return std::vector<vtkSmartPointer<vtkDataObject>>{ Copy(sample->GetOutput()) };
      }, 25 * 17);
    }
  }
}
