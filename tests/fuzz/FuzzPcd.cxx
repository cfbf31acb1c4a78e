// SPDX-License-Identifier: BSD-3-Clause
/**
 * libFuzzer target over vtkPCDReader and vtkPCDWriter (the module's sources, compiled in here with
 * instrumentation). The first byte chooses the options: bit 0 keeps NaN points, bits 1-2 the
 * DATA kind the writer uses (ascii, binary, binary_compressed, modulo 3); the rest is the file.
 *
 * Contracts checked beyond ASan/UBSan (a broken one aborts, i.e. is a crash for libFuzzer):
 * - the update either fails and leaves an empty output, or succeeds; no other outcome (a crash,
 *   an exception escaping, a huge allocation that ASan reports);
 * - what it read adds up: points kept + points skipped = POINTS of the header, and every array
 *   has one tuple per point;
 * - what it read, written in any DATA kind and read back, has the same points and arrays, bit for
 *   bit (up to 4096 points, to keep the rate of inputs high);
 * - the bytes after the first, taken as an LZF block, decode to the same count and bytes with the
 *   reader's decoder and with liblzf's (the first byte sets the room).
 */
#include "FuzzContract.h"
#include "PointSetSurfacesPCDBody.h"

#include "vtkDataArray.h"
#include "vtkExecutive.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkPCDReader.h"
#include "vtkPCDWriter.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"
#include "vtkVariant.h"

extern "C"
{
#include <lzf.h>
}

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <unistd.h>
#include <vector>

const char* const FuzzTargetName = "pss_fuzz_pcd";

namespace
{

std::string Folder;

// Reads @p path; @p ok says whether the update succeeded (the executive's status: with
// vtkObject's global warning display off, vtkErrorMacro invokes no ErrorEvent to count).
vtkSmartPointer<vtkPolyData> Read(const std::string& path, bool skipNaN, bool& ok, vtkIdType& inFile, vtkIdType& skipped)
{
  vtkNew<vtkPCDReader> reader;
  reader->SetFileName(path.c_str());
  reader->SetSkipNaNPoints(skipNaN);
  ok = reader->GetExecutive()->Update() == 1;
  inFile = reader->GetNumberOfPointsInFile();
  skipped = reader->GetNumberOfSkippedPoints();
  return reader->GetOutput();
}

// Bit for bit; with @p anyNaN, two NaNs of a floating-point array are equal whatever their bits.
bool SameBits(vtkDataArray* a, vtkDataArray* b, bool anyNaN)
{
  if (!a || !b || a->GetNumberOfValues() != b->GetNumberOfValues() ||
    a->GetNumberOfComponents() != b->GetNumberOfComponents() || a->GetDataTypeSize() != b->GetDataTypeSize())
  {
    return false;
  }
  const std::size_t size = static_cast<std::size_t>(a->GetDataTypeSize());
  const auto* pa = static_cast<const unsigned char*>(a->GetVoidPointer(0));
  const auto* pb = static_cast<const unsigned char*>(b->GetVoidPointer(0));
  const bool floating = a->GetDataType() == VTK_FLOAT || a->GetDataType() == VTK_DOUBLE;
  for (vtkIdType i = 0; i < a->GetNumberOfValues(); ++i)
  {
    const std::size_t k = static_cast<std::size_t>(i) * size;
    if (std::memcmp(pa + k, pb + k, size) != 0 &&
      !(anyNaN && floating && std::isnan(a->GetVariantValue(i).ToDouble()) && std::isnan(b->GetVariantValue(i).ToDouble())))
    {
      return false;
    }
  }
  return true;
}

// The reader's LZF decoder against liblzf's on the input taken as an LZF block (after the first
// byte, which sets the room): the same count and bytes, whatever the block.
void CompareLzfDecoders(const std::uint8_t* data, std::size_t size)
{
  if (size < 2)
  {
    return; // liblzf reads a control byte even from an empty block
  }
  const std::size_t room = (size - 1) * (1 + data[0] % 8);
  std::vector<unsigned char> ours(room), theirs(room);
  const std::size_t n = pss_pcd::detail::DecodeLzf(data + 1, size - 1, ours.data(), room);
  const unsigned int m =
    lzf_decompress(data + 1, static_cast<unsigned int>(size - 1), theirs.data(), static_cast<unsigned int>(room));
  PSS_FUZZ_CHECK(n == m);
  PSS_FUZZ_CHECK(std::memcmp(ours.data(), theirs.data(), n) == 0);
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***)
{
  vtkObject::GlobalWarningDisplayOff();
  Folder = MakeScratchFolder("pss-fuzz-pcd");
  std::atexit([]() {
    std::remove((Folder + "/input.pcd").c_str());
    std::remove((Folder + "/again.pcd").c_str());
    rmdir(Folder.c_str());
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  if (size == 0)
  {
    return 0;
  }
  CompareLzfDecoders(data, size);
  const bool skipNaN = (data[0] & 1) == 0;
  const int mode = (data[0] >> 1) % 3;
  const std::string path = Folder + "/input.pcd";
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 1), static_cast<std::streamsize>(size - 1));
    if (!out)
    {
      FuzzFail("cannot write the fuzz input to a temporary file", __LINE__);
    }
  }
  bool ok = false;
  vtkIdType inFile = 0, skipped = 0;
  vtkSmartPointer<vtkPolyData> read = Read(path, skipNaN, ok, inFile, skipped);
  PSS_FUZZ_CHECK(read != nullptr);
  if (!ok)
  {
    PSS_FUZZ_CHECK(read->GetNumberOfPoints() == 0);
    return 0;
  }
  const vtkIdType n = read->GetNumberOfPoints();
  PSS_FUZZ_CHECK(n + skipped == inFile);
  PSS_FUZZ_CHECK(skipNaN || skipped == 0);
  vtkPointData* pd = read->GetPointData();
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
  {
    PSS_FUZZ_CHECK(pd->GetAbstractArray(a)->GetNumberOfTuples() == n);
  }
  if (n > 4096)
  {
    return 0;
  }
  const std::string again = Folder + "/again.pcd";
  vtkNew<vtkPCDWriter> writer;
  writer->SetInputData(read);
  writer->SetFileName(again.c_str());
  writer->SetDataMode(mode);
  PSS_FUZZ_CHECK(writer->Write() == 1 && writer->GetErrorCode() == 0);
  vtkIdType inFile2 = 0, skipped2 = 0;
  vtkSmartPointer<vtkPolyData> back = Read(again, skipNaN, ok, inFile2, skipped2);
  PSS_FUZZ_CHECK(ok);
  PSS_FUZZ_CHECK(back->GetNumberOfPoints() == n);
  // ASCII writes a NaN as "nan": its sign and payload do not survive, every other bit does.
  const bool anyNaN = mode == 0;
  if (n > 0)
  {
    PSS_FUZZ_CHECK(read->GetPoints()->GetDataType() == back->GetPoints()->GetDataType());
    PSS_FUZZ_CHECK(SameBits(read->GetPoints()->GetData(), back->GetPoints()->GetData(), anyNaN));
  }
  for (int a = 0; a < pd->GetNumberOfArrays(); ++a)
  {
    if (vtkDataArray* array = pd->GetArray(a))
    {
      PSS_FUZZ_CHECK(SameBits(array, back->GetPointData()->GetArray(pd->GetArrayName(a)), anyNaN));
    }
  }
  return 0;
}
