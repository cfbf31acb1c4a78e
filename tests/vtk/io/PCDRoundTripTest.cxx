// SPDX-License-Identifier: BSD-3-Clause
/**
 * vtkPCDReader and vtkPCDWriter: clouds written and read back bit for bit in each DATA kind
 * (ordinary and organized, with every field type PCD has), and files written byte by byte here
 * (not by the writer) read to the values they hold.
 */
#include "PCDTestUtilities.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdTypeArray.h"
#include "vtkIntArray.h"
#include "vtkPCDWriter.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkShortArray.h"
#include "vtkSignedCharArray.h"
#include "vtkTypeInt64Array.h"
#include "vtkTypeUInt64Array.h"
#include "vtkUnsignedCharArray.h"
#include "vtkUnsignedIntArray.h"
#include "vtkUnsignedShortArray.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

using namespace pcd_test;

namespace
{

template <typename ArrayT>
void AddArray(vtkPolyData* poly, const char* name, int components, double scale)
{
  vtkNew<ArrayT> array;
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(poly->GetNumberOfPoints());
  for (vtkIdType i = 0; i < array->GetNumberOfValues(); ++i)
  {
    array->SetValue(i, static_cast<typename ArrayT::ValueType>(std::fmod(i * scale, 120.0) - (scale < 0 ? 60 : 0)));
  }
  poly->GetPointData()->AddArray(array);
}

// A cloud with points of @p pointType and an array of every type PCD holds.
vtkSmartPointer<vtkPolyData> RichCloud(int pointType, vtkIdType n)
{
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  vtkNew<vtkPoints> points;
  points->SetDataType(pointType);
  for (vtkIdType i = 0; i < n; ++i)
  {
    points->InsertNextPoint(0.1 * i + 1e-7, std::sin(0.3 * i), 1.0 / 3.0 + i);
  }
  poly->SetPoints(points);
  AddArray<vtkUnsignedCharArray>(poly, "RGB", 3, 7.0);
  AddArray<vtkFloatArray>(poly, "Normals", 3, 0.37);
  AddArray<vtkUnsignedIntArray>(poly, "label", 1, 3.0);
  AddArray<vtkFloatArray>(poly, "intensity", 1, 0.1);
  AddArray<vtkDoubleArray>(poly, "histogram", 5, 1.0 / 7.0);
  AddArray<vtkShortArray>(poly, "pair", 2, -3.0);
  AddArray<vtkSignedCharArray>(poly, "small", 1, -1.0);
  AddArray<vtkUnsignedShortArray>(poly, "ring", 1, 5.0);
  AddArray<vtkTypeUInt64Array>(poly, "stamp", 1, 11.0);
  AddArray<vtkTypeInt64Array>(poly, "offset", 1, -13.0);
  poly->GetPointData()->SetActiveScalars("RGB");
  poly->GetPointData()->SetActiveNormals("Normals");
  vtkNew<vtkDoubleArray> viewpoint;
  viewpoint->SetName("Viewpoint");
  for (double v : { 0.5, -1.0, 2.0, 0.0, 1.0, 0.0, 0.0 })
  {
    viewpoint->InsertNextValue(v);
  }
  poly->GetFieldData()->AddArray(viewpoint);
  return poly;
}

void Write(vtkPolyData* poly, const std::string& path, int mode)
{
  vtkNew<vtkPCDWriter> writer;
  vtkNew<ErrorObserver> errors;
  errors->Attach(writer);
  writer->SetInputData(poly);
  writer->SetFileName(path.c_str());
  writer->SetDataMode(mode);
  writer->Write();
  ASSERT_TRUE(errors->Errors.empty()) << errors->Errors.front();
}

bool SameBits(vtkDataArray* a, vtkDataArray* b)
{
  return a && b && a->GetNumberOfValues() == b->GetNumberOfValues() &&
    a->GetNumberOfComponents() == b->GetNumberOfComponents() && a->GetDataTypeSize() == b->GetDataTypeSize() &&
    std::memcmp(a->GetVoidPointer(0), b->GetVoidPointer(0),
      static_cast<std::size_t>(a->GetNumberOfValues()) * static_cast<std::size_t>(a->GetDataTypeSize())) == 0;
}

void ExpectSameCloud(vtkPolyData* expected, vtkPolyData* actual)
{
  ASSERT_EQ(expected->GetNumberOfPoints(), actual->GetNumberOfPoints());
  EXPECT_EQ(actual->GetNumberOfVerts(), actual->GetNumberOfPoints());
  EXPECT_EQ(expected->GetPoints()->GetDataType(), actual->GetPoints()->GetDataType());
  EXPECT_TRUE(SameBits(expected->GetPoints()->GetData(), actual->GetPoints()->GetData()));
  vtkPointData* pd = expected->GetPointData();
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
  {
    const char* name = pd->GetArrayName(a);
    EXPECT_TRUE(SameBits(pd->GetArray(a), actual->GetPointData()->GetArray(name))) << name;
  }
  EXPECT_EQ(pd->GetNumberOfArrays(), actual->GetPointData()->GetNumberOfArrays());
  vtkDataArray* v = actual->GetFieldData()->GetArray("Viewpoint");
  vtkDataArray* w = expected->GetFieldData()->GetArray("Viewpoint");
  ASSERT_NE(v, nullptr);
  for (vtkIdType k = 0; k < 7; ++k)
  {
    EXPECT_EQ(w->GetComponent(k, 0), v->GetComponent(k, 0));
  }
}

} // namespace

TEST(PCDRoundTrip, EveryDataKindKeepsEveryArrayBitwise)
{
  for (int pointType : { VTK_FLOAT, VTK_DOUBLE })
  {
    const auto cloud = RichCloud(pointType, 257);
    for (int mode : { vtkPCDWriter::ASCII, vtkPCDWriter::BINARY, vtkPCDWriter::BINARY_COMPRESSED })
    {
      SCOPED_TRACE("points " + std::to_string(pointType) + ", DataMode " + std::to_string(mode));
      const std::string path = TestPath("roundtrip_" + std::to_string(pointType) + "_" + std::to_string(mode) + ".pcd");
      Write(cloud, path, mode);
      const Read r = ReadPCD(path);
      ASSERT_TRUE(r.ok) << r.errors->Errors.front();
      ExpectSameCloud(cloud, r.output);
      EXPECT_NE(r.output->GetPointData()->GetNormals(), nullptr);
      EXPECT_NE(r.output->GetPointData()->GetScalars(), nullptr);
      // Written again from what was read: the same file, byte for byte.
      const std::string again = path + ".again.pcd";
      Write(r.output, again, mode);
      std::ifstream a(path, std::ios::binary), b(again, std::ios::binary);
      const std::string first((std::istreambuf_iterator<char>(a)), {}), second((std::istreambuf_iterator<char>(b)), {});
      EXPECT_TRUE(first == second) << "the file written from what was read differs (" << first.size() << " and "
                                   << second.size() << " bytes)";
    }
  }
}

TEST(PCDRoundTrip, OrganizedCloudKeepsItsImageAndMissingPixels)
{
  // A 4 x 3 image whose pixels 5 and 10 saw nothing.
  const std::string header = "VERSION 0.7\nFIELDS x y z intensity\nSIZE 4 4 4 4\nTYPE F F F F\nCOUNT 1 1 1 1\n"
                             "WIDTH 4\nHEIGHT 3\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS 12\nDATA binary\n";
  std::string body;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int i = 0; i < 12; ++i)
  {
    const bool missing = i == 5 || i == 10;
    body += Bytes(missing ? nan : 0.1f * i) + Bytes(missing ? nan : 1.0f) + Bytes(missing ? nan : 2.0f + i) + Bytes(1.5f * i);
  }
  const Read r = ReadBytes("organized.pcd", header + body);
  ASSERT_TRUE(r.ok) << r.errors->Errors.front();
  ASSERT_EQ(r.output->GetNumberOfPoints(), 10);
  EXPECT_EQ(r.reader->GetNumberOfSkippedPoints(), 2);
  EXPECT_EQ(r.reader->GetNumberOfPointsInFile(), 12);
  vtkDataArray* pixel = r.output->GetPointData()->GetArray("Pixel");
  ASSERT_NE(pixel, nullptr);
  // Point 5 of the output is pixel 6 of the image: column 2, row 1.
  EXPECT_EQ(pixel->GetComponent(5, 0), 2);
  EXPECT_EQ(pixel->GetComponent(5, 1), 1);
  vtkDataArray* grid = r.output->GetFieldData()->GetArray("GridDimensions");
  ASSERT_NE(grid, nullptr);
  EXPECT_EQ(grid->GetComponent(0, 0), 4);
  EXPECT_EQ(grid->GetComponent(1, 0), 3);

  for (int mode : { vtkPCDWriter::ASCII, vtkPCDWriter::BINARY, vtkPCDWriter::BINARY_COMPRESSED })
  {
    const std::string path = TestPath("organized_again_" + std::to_string(mode) + ".pcd");
    Write(r.output, path, mode);
    const Read back = ReadPCD(path);
    ASSERT_TRUE(back.ok);
    ExpectSameCloud(r.output, back.output);
    const Read whole = ReadPCD(path, false);
    ASSERT_EQ(whole.output->GetNumberOfPoints(), 12);
    double p[3];
    whole.output->GetPoint(10, p);
    EXPECT_TRUE(std::isnan(p[0]));
    whole.output->GetPoint(11, p);
    EXPECT_EQ(p[2], 13.0);
  }
}

TEST(PCDRoundTrip, HandWrittenFilesInEachDataKind)
{
  // Unusual order and sizes: a 2-element U2, z before x, a double y, a signed byte, float rgb bits.
  const std::string fields = "VERSION .7\nFIELDS ring z x y flag rgb\nSIZE 2 4 4 8 1 4\nTYPE U F F F I F\n"
                             "COUNT 2 1 1 1 1 1\nWIDTH 3\nHEIGHT 1\nPOINTS 3\n";
  const std::uint16_t ring[3][2] = { { 1, 65535 }, { 7, 0 }, { 300, 2 } };
  const float z[3] = { -1.5f, 0.25f, 3e10f };
  const float x[3] = { 10.f, 20.f, 30.f };
  const double y[3] = { 0.1, -0.2, 1e-300 };
  const std::int8_t flag[3] = { -128, 0, 127 };
  const std::uint32_t rgb[3] = { 0x00ff8000u, 0x00010203u, 0xff000000u };

  std::string pointMajor, fieldMajor[6];
  for (int i = 0; i < 3; ++i)
  {
    const std::string cols[6] = { Bytes(ring[i][0]) + Bytes(ring[i][1]), Bytes(z[i]), Bytes(x[i]), Bytes(y[i]),
      Bytes(flag[i]), Bytes(rgb[i]) };
    for (int f = 0; f < 6; ++f)
    {
      pointMajor += cols[f];
      fieldMajor[f] += cols[f];
    }
  }
  std::string raw;
  for (const std::string& column : fieldMajor)
  {
    raw += column;
  }
  // The ASCII file declares rgb as U (its integer), with a blank line among the points.
  const std::string ascii = "1 65535 -1.5 10 0.1 -128 " + std::to_string(rgb[0]) + "\n7 0 0.25 20 -0.2 0 " +
    std::to_string(rgb[1]) + "\n\n300 2 3e10 30 1e-300 127 " + std::to_string(rgb[2]) + "\n";
  const std::string asciiHeader = "VERSION .7\nFIELDS ring z x y flag rgb\nSIZE 2 4 4 8 1 4\nTYPE U F F F I U\n"
                                  "COUNT 2 1 1 1 1 1\nWIDTH 3\nHEIGHT 1\nPOINTS 3\n";
  const std::string files[3] = { asciiHeader + "DATA ascii\n" + ascii, fields + "DATA binary\n" + pointMajor,
    fields + "DATA binary_compressed\n" + CompressedBody(raw) };
  for (int kind = 0; kind < 3; ++kind)
  {
    SCOPED_TRACE("DATA kind " + std::to_string(kind));
    const Read r = ReadBytes("hand_" + std::to_string(kind) + ".pcd", files[kind]);
    ASSERT_TRUE(r.ok) << r.errors->Errors.front();
    vtkPolyData* out = r.output;
    ASSERT_EQ(out->GetNumberOfPoints(), 3);
    EXPECT_EQ(out->GetPoints()->GetDataType(), VTK_DOUBLE); // y is a double
    for (vtkIdType i = 0; i < 3; ++i)
    {
      double p[3];
      out->GetPoint(i, p);
      EXPECT_EQ(p[0], x[i]);
      EXPECT_EQ(p[1], y[i]);
      EXPECT_EQ(p[2], z[i]);
    }
    vtkDataArray* ringArray = out->GetPointData()->GetArray("ring");
    ASSERT_NE(ringArray, nullptr);
    EXPECT_EQ(ringArray->GetDataType(), VTK_UNSIGNED_SHORT);
    EXPECT_EQ(ringArray->GetNumberOfComponents(), 2);
    EXPECT_EQ(ringArray->GetComponent(0, 1), 65535);
    EXPECT_EQ(ringArray->GetComponent(2, 0), 300);
    vtkDataArray* flagArray = out->GetPointData()->GetArray("flag");
    ASSERT_NE(flagArray, nullptr);
    EXPECT_EQ(flagArray->GetDataType(), VTK_SIGNED_CHAR);
    EXPECT_EQ(flagArray->GetComponent(0, 0), -128);
    auto* colors = vtkUnsignedCharArray::SafeDownCast(out->GetPointData()->GetArray("RGB"));
    ASSERT_NE(colors, nullptr);
    EXPECT_EQ(colors->GetTypedComponent(0, 0), 0xff);
    EXPECT_EQ(colors->GetTypedComponent(0, 1), 0x80);
    EXPECT_EQ(colors->GetTypedComponent(0, 2), 0x00);
    EXPECT_EQ(colors->GetTypedComponent(1, 2), 0x03);
    EXPECT_EQ(colors->GetTypedComponent(2, 0), 0x00); // alpha is not a colour of rgb
    EXPECT_EQ(out->GetFieldData()->GetArray("Viewpoint"), nullptr) << "no VIEWPOINT line";
  }
}

TEST(PCDRoundTrip, OlderHeadersAndPaddingFields)
{
  // Version 0.5 style: COLUMNS instead of FIELDS, no COUNT, no WIDTH/HEIGHT; PCL's padding "_".
  const std::string file = "# a comment\nVERSION .5\nCOLUMNS x y z _ _\nSIZE 4 4 4 4 4\nTYPE F F F U U\n"
                           "POINTS 2\nDATA ascii\n1 2 3 9 9\n4 5 6 9 9\n";
  const Read r = ReadBytes("v05.pcd", file);
  ASSERT_TRUE(r.ok) << r.errors->Errors.front();
  ASSERT_EQ(r.output->GetNumberOfPoints(), 2);
  EXPECT_EQ(r.output->GetPointData()->GetNumberOfArrays(), 0);
  double p[3];
  r.output->GetPoint(1, p);
  EXPECT_EQ(p[0], 4);
  EXPECT_EQ(p[2], 6);
  EXPECT_EQ(r.output->GetFieldData()->GetArray("GridDimensions")->GetComponent(0, 0), 2);
}

TEST(PCDRoundTrip, NaNPointsKeptOnRequest)
{
  const std::string file = "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\nWIDTH 3\nHEIGHT 1\n"
                           "POINTS 3\nDATA ascii\n1 2 3\nnan nan nan\n4 inf 6\n";
  const Read skipped = ReadBytes("nan.pcd", file);
  ASSERT_TRUE(skipped.ok);
  EXPECT_EQ(skipped.output->GetNumberOfPoints(), 1);
  EXPECT_EQ(skipped.reader->GetNumberOfSkippedPoints(), 2);
  EXPECT_EQ(skipped.output->GetFieldData()->GetArray("SkippedPoints")->GetComponent(0, 0), 2);
  EXPECT_EQ(skipped.output->GetPointData()->GetArray("Pixel"), nullptr) << "not organized";
  const Read kept = ReadBytes("nan.pcd", file, false);
  ASSERT_TRUE(kept.ok);
  EXPECT_EQ(kept.output->GetNumberOfPoints(), 3);
  EXPECT_EQ(kept.reader->GetNumberOfSkippedPoints(), 0);
}

TEST(PCDRoundTrip, OrganizedImageWithoutAnyValidPixel)
{
  // Every pixel NaN: nothing is read; written again it is still a 2 x 2 image of NaN pixels (the
  // writer once left the unfilled image's bytes as they were: found by Fuzz.pcd).
  const std::string nan = Bytes(std::numeric_limits<float>::quiet_NaN());
  std::string body;
  for (int i = 0; i < 4; ++i)
  {
    body += nan + nan + nan;
  }
  const Read r = ReadBytes("all-nan.pcd", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nWIDTH 2\nHEIGHT 2\nDATA binary\n" + body);
  ASSERT_TRUE(r.ok);
  ASSERT_EQ(r.output->GetNumberOfPoints(), 0);
  for (int mode : { vtkPCDWriter::ASCII, vtkPCDWriter::BINARY, vtkPCDWriter::BINARY_COMPRESSED })
  {
    const std::string path = TestPath("all-nan-again-" + std::to_string(mode) + ".pcd");
    Write(r.output, path, mode);
    EXPECT_EQ(ReadPCD(path).output->GetNumberOfPoints(), 0);
    const Read whole = ReadPCD(path, false);
    ASSERT_EQ(whole.output->GetNumberOfPoints(), 4);
    double p[3];
    whole.output->GetPoint(3, p);
    EXPECT_TRUE(std::isnan(p[0]) && std::isnan(p[1]) && std::isnan(p[2]));
  }
}
