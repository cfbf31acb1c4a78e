// SPDX-License-Identifier: BSD-3-Clause
#include "PaperOutput.h"

#include "vtkPointSetSurfaceEnergyGlyphs.h"
#include "vtkPointSetSurfaceFieldSampler.h"

#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkStringArray.h"
#include "vtkXMLImageDataWriter.h"
#include "vtkXMLPolyDataWriter.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <stdexcept>

#include <unistd.h>

namespace pss_paper
{

namespace fs = std::filesystem;

fs::path OutDir = "paper-figures";

// Writes to a temporary name, then renames: a reader (or a second demo writing the same folder)
// never sees a half-written file.
namespace
{

template <class WriterT, class DataT>
void WriteXML(DataT* data, const std::string& name)
{
  const fs::path target = OutDir / name;
  const fs::path temporary = OutDir / ("." + name + ".tmp" + std::to_string(getpid()));
  vtkNew<WriterT> writer;
  writer->SetFileName(temporary.string().c_str());
  writer->SetInputData(data);
  writer->SetDataModeToAppended();
  writer->SetCompressorTypeToZLib();
  if (!writer->Write() || writer->GetErrorCode() != 0)
  {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw std::runtime_error("cannot write " + target.string());
  }
  fs::rename(temporary, target);
}

} // namespace

void Write(vtkPolyData* data, const std::string& name)
{
  WriteXML<vtkXMLPolyDataWriter>(data, name);
}

void Write(vtkImageData* data, const std::string& name)
{
  WriteXML<vtkXMLImageDataWriter>(data, name);
}

// A title and the h of a figure's data, as field data (the renderer reads them).
void Label(vtkDataObject* data, const std::string& title, double h)
{
  vtkNew<vtkStringArray> t;
  t->SetName("Title");
  t->InsertNextValue(title);
  data->GetFieldData()->AddArray(t);
  vtkNew<vtkDoubleArray> s;
  s->SetName("SceneH");
  s->InsertNextValue(h);
  data->GetFieldData()->AddArray(s);
}

double Percentile(std::vector<double> v, double q)
{
  if (v.empty())
  {
    return 0.0;
  }
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

void AddLogEnergy(vtkDataSet* field)
{
  vtkDataArray* energy = field->GetPointData()->GetArray("Energy");
  if (!energy)
  {
    throw std::runtime_error("the sampled field has no Energy array");
  }
  double floor = std::numeric_limits<double>::infinity();
  for (vtkIdType i = 0; i < energy->GetNumberOfTuples(); ++i)
  {
    const double e = energy->GetTuple1(i);
    if (e > 0.0)
    {
      floor = std::min(floor, e);
    }
  }
  if (!std::isfinite(floor))
  {
    floor = 1e-300;
  }
  vtkNew<vtkDoubleArray> logEnergy;
  logEnergy->SetName("LogEnergy");
  logEnergy->SetNumberOfTuples(energy->GetNumberOfTuples());
  for (vtkIdType i = 0; i < energy->GetNumberOfTuples(); ++i)
  {
    logEnergy->SetValue(i, std::log10(std::max(energy->GetTuple1(i), floor)));
  }
  field->GetPointData()->AddArray(logEnergy);
}

vtkSmartPointer<vtkImageData> SampleField(const Scene& scene, int variant, double spacingInH)
{
  const std::vector<double> b = GrownBounds(scene, kStartMargin);
  const double spacing = spacingInH * scene.h;
  const int nx = static_cast<int>(std::lround((b[1] - b[0]) / spacing)) + 1;
  const int ny = static_cast<int>(std::lround((b[3] - b[2]) / spacing)) + 1;
  vtkNew<vtkPointSetSurfaceFieldSampler> sampler;
  sampler->SetSurface(MakeSurface(scene, variant));
  sampler->SetSourceData(scene.cloud);
  sampler->GenerateSamplingGridOn();
  sampler->SetSampleDimensions(nx, ny, 1);
  sampler->SetSamplingMargin(kStartMargin);
  sampler->SetOrientationModeToPropagate();
  sampler->Update();
  auto field = vtkSmartPointer<vtkImageData>::New();
  field->DeepCopy(vtkImageData::SafeDownCast(sampler->GetOutput()));
  if (field->GetNumberOfPoints() != static_cast<vtkIdType>(nx) * ny)
  {
    throw std::runtime_error("the field sampler failed on scene " + scene.name);
  }

  AddLogEnergy(field);
  Label(field, VariantTitle(variant), scene.h);
  return field;
}

Glyphs EnergyGlyphs(const Scene& scene, int variant, const std::vector<pss::Vec3>& samples, double glyphSizeInH,
  double segmentLengthInH)
{
  vtkNew<vtkPointSetSurfaceEnergyGlyphs> glyphs;
  glyphs->SetSurface(MakeSurface(scene, variant));
  glyphs->SetInputData(scene.cloud);
  glyphs->SetSamplePointsData(MakePointCloud(samples));
  glyphs->SetResolution(96);
  glyphs->SetScaleModeToPerGlyph();
  glyphs->SetGlyphSize(glyphSizeInH);
  glyphs->SetSegmentLength(segmentLengthInH);
  glyphs->Update();
  Glyphs out;
  out.glyphs = vtkSmartPointer<vtkPolyData>::New();
  out.glyphs->DeepCopy(glyphs->GetOutput(0));
  out.fits = vtkSmartPointer<vtkPolyData>::New();
  out.fits->DeepCopy(glyphs->GetOutput(1));
  Label(out.glyphs, VariantTitle(variant), scene.h);
  return out;
}

std::string Fixed(double v, int digits)
{
  if (std::isnan(v))
  {
    return "-";
  }
  if (std::isinf(v))
  {
    return "none";
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

std::string JsonNumber(double v)
{
  if (!std::isfinite(v))
  {
    return "null";
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string JsonString(const std::string& s)
{
  std::string out = "\"";
  for (char c : s)
  {
    if (c == '"' || c == '\\')
    {
      out += '\\';
    }
    out += c;
  }
  return out + "\"";
}

bool PrintAndWriteChecks(const std::vector<Check>& checks)
{
  std::printf("\nchecked claims\n");
  bool all = true;
  std::ofstream json(OutDir / "paper_checks.json");
  json << "{\n  \"checks\": [\n";
  for (std::size_t i = 0; i < checks.size(); ++i)
  {
    const Check& c = checks[i];
    all = all && c.pass;
    std::printf("  [%s] %-38s %10s   (%s)  %s\n", c.pass ? "PASS" : "FAIL", c.name.c_str(), Fixed(c.value, 4).c_str(),
      c.bound.c_str(), c.claim.c_str());
    json << "    {\"name\": " << JsonString(c.name) << ", \"claim\": " << JsonString(c.claim)
         << ", \"value\": " << JsonNumber(c.value) << ", \"bound\": " << JsonString(c.bound)
         << ", \"pass\": " << (c.pass ? "true" : "false") << "}" << (i + 1 < checks.size() ? "," : "") << "\n";
  }
  json << "  ],\n  \"all_pass\": " << (all ? "true" : "false") << "\n}\n";
  return all;
}

double Since(Clock::time_point t0)
{
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

Clock::time_point ProgramStart = Clock::now();
namespace
{
Clock::time_point LastStep = ProgramStart;
}
void Done(const std::string& what)
{
  std::printf("  [%6.1f s] %-58s %6.1f s\n", Since(ProgramStart), what.c_str(), Since(LastStep));
  std::fflush(stdout);
  LastStep = Clock::now();
}

} // namespace pss_paper
