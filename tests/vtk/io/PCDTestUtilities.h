// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PCDTestUtilities.h
 * @brief Files written byte by byte for the PCD tests, and a reader run that records its errors.
 */
#pragma once

#include "../filters/ErrorObserver.h"

#include "vtkNew.h"
#include "vtkPCDReader.h"
#include "vtkPolyData.h"
#include "vtkSmartPointer.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <vector>

namespace pcd_test
{

/// A path under the build tree's Testing/ for a test file called @p name.
inline std::string TestPath(const std::string& name)
{
  return std::string(PSS_BINARY_DIR) + "/Testing/pcd-" + name;
}

inline void WriteBytes(const std::string& path, const std::string& bytes)
{
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

/// The little-endian bytes of @p value.
template <typename T>
std::string Bytes(T value)
{
  std::string out(sizeof value, '\0');
  std::memcpy(&out[0], &value, sizeof value);
  return out;
}

/// An LZF block made of literal runs only (a control byte of length - 1, then up to 32 bytes):
/// valid LZF that any decompressor reads, written without a compressor.
inline std::string LiteralLzf(const std::string& raw)
{
  std::string out;
  for (std::size_t i = 0; i < raw.size(); i += 32)
  {
    const std::size_t n = std::min<std::size_t>(32, raw.size() - i);
    out += static_cast<char>(n - 1);
    out += raw.substr(i, n);
  }
  return out;
}

/// The two sizes and the block of a binary_compressed body holding @p raw (field-major bytes).
inline std::string CompressedBody(const std::string& raw)
{
  const std::string block = LiteralLzf(raw);
  return Bytes(static_cast<std::uint32_t>(block.size())) + Bytes(static_cast<std::uint32_t>(raw.size())) + block;
}

/// The result of reading one file.
struct Read
{
  vtkSmartPointer<vtkPolyData> output;
  vtkSmartPointer<ErrorObserver> errors;
  vtkSmartPointer<vtkPCDReader> reader;
  bool ok = false;
};

inline Read ReadPCD(const std::string& path, bool skipNaN = true)
{
  Read r;
  r.reader = vtkSmartPointer<vtkPCDReader>::New();
  r.errors = vtkSmartPointer<ErrorObserver>::New();
  r.errors->Attach(r.reader);
  r.reader->SetFileName(path.c_str());
  r.reader->SetSkipNaNPoints(skipNaN);
  r.reader->Update();
  r.output = r.reader->GetOutput();
  r.ok = r.errors->Errors.empty();
  return r;
}

/// Reads a file whose bytes are @p bytes.
inline Read ReadBytes(const std::string& name, const std::string& bytes, bool skipNaN = true)
{
  const std::string path = TestPath(name);
  WriteBytes(path, bytes);
  return ReadPCD(path, skipNaN);
}

}
