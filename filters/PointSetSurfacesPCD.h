// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PointSetSurfacesPCD.h
 * @brief The PCD file format (PCL's point cloud files, versions 0.5 to 0.7) without VTK: the
 *        header parsed and checked, the body decoded into one column per field, and both written.
 *
 * vtkPCDReader and vtkPCDWriter turn these columns into VTK arrays and back; the fuzz target
 * `pss_fuzz_pcd` reads files through them. Everything a file claims (counts, sizes, the
 * compressed block's two sizes) is checked against the file's own size before a byte is
 * allocated for it, so a lying header fails with a message instead of exhausting memory.
 */
#ifndef PointSetSurfacesPCD_h
#define PointSetSurfacesPCD_h

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace pss_pcd
{

/// How the body is stored (the DATA line).
enum class DataKind
{
  Ascii,
  Binary,           ///< point-major: every field of point 0, then point 1, ...
  BinaryCompressed  ///< field-major, one LZF block
};

/// One FIELDS entry with its SIZE, TYPE and COUNT.
struct Field
{
  std::string name;
  char type = 'F';        ///< 'I' signed, 'U' unsigned, 'F' floating point
  std::size_t size = 4;   ///< bytes per element: 1, 2, 4 or 8 (F: 4 or 8)
  std::size_t count = 1;  ///< elements per point

  std::size_t bytesPerPoint() const { return this->size * this->count; }
};

/// Everything the header says.
struct Header
{
  std::string version;                ///< as written (".7", "0.7", ...)
  std::vector<Field> fields;
  std::uint64_t width = 0;
  std::uint64_t height = 1;
  std::uint64_t points = 0;
  bool hasViewpoint = false;
  std::array<double, 7> viewpoint{ { 0, 0, 0, 1, 0, 0, 0 } }; ///< tx ty tz qw qx qy qz
  DataKind data = DataKind::Binary;

  /// Sum of the fields' bytes per point (the binary record; no padding).
  std::size_t pointSize() const;
  /// True for an organized cloud (rows of an image: HEIGHT > 1).
  bool organized() const { return this->height > 1; }
};

/// An allocator that leaves new bytes uninitialized: a body of hundreds of megabytes is written
/// over at once (decompressed or copied into), so zeroing it first would only cost time.
template <typename T>
struct UninitializedAllocator : std::allocator<T>
{
  template <typename U>
  struct rebind
  {
    using other = UninitializedAllocator<U>;
  };
  UninitializedAllocator() = default;
  template <typename U>
  UninitializedAllocator(const UninitializedAllocator<U>&) noexcept
  {
  }
  template <typename U>
  void construct(U* p) noexcept
  {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
};

/// Bytes of a body.
using Bytes = std::vector<unsigned char, UninitializedAllocator<unsigned char>>;

/// The body as columns: field f's values for every point, contiguous (points x count elements of
/// its size, in the file's little-endian byte order), at bytes[start[f]].
struct Columns
{
  Bytes bytes;
  std::vector<std::size_t> start;
};

/// A whole file: its header and its body.
struct Cloud
{
  Header header;
  Columns columns;
};

/**
 * Parses and checks the header at the start of @p file (@p size bytes) and returns it; @p bodyOffset
 * receives where the body begins. Throws std::runtime_error naming the line that is wrong.
 */
Header ParseHeader(const unsigned char* file, std::size_t size, std::size_t& bodyOffset);

/// Where each field's column starts in the field-major body of @p header's POINTS points.
std::vector<std::size_t> ColumnStarts(const Header& header);

/// Decodes a whole file held in memory; throws std::runtime_error with a readable message.
Cloud Decode(const unsigned char* file, std::size_t size);

/// Reads and decodes @p path; the message of any error names the file.
Cloud ReadFile(const std::string& path);

/// The header text of @p header (ending with the DATA line and its newline).
std::string FormatHeader(const Header& header);

/// The file bytes of @p cloud in cloud.header.data's kind; throws std::runtime_error when the
/// columns do not match the header.
std::vector<unsigned char> Encode(const Cloud& cloud);

/// The name of a DATA kind as the DATA line writes it.
const char* DataKindName(DataKind kind);

}

#endif
