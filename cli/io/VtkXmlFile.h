// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file VtkXmlFile.h
 * @brief A VTK XML file (.vtp .vtu .vti) as VTK's readers see it, for checking it before they
 *        read it: the element tree from vtkXMLDataParser, and each array's encoded data read with
 *        VTK's own input streams (vtkBase64InputStream, vtkInputStream) and compressors.
 *
 * VtkXml.cxx checks the datasets (pieces, cells, images) on top of what is here: the arrays, their
 * size headers and the bytes they hold.
 */
#ifndef pss_cli_io_VtkXmlFile_h
#define pss_cli_io_VtkXmlFile_h

#include "vtkSmartPointer.h"

#include <cstdint>
#include <fstream>
#include <functional>
#include <optional>
#include <string>
#include <vector>

class vtkXMLDataElement;
class vtkXMLDataParser;

namespace pss_cli
{
namespace io
{
namespace vtkxml
{

enum class Compressor
{
  None,
  ZLib,
  LZ4,
  LZMA
};

/// VTK's class name of @p c, as the root's compressor attribute names it.
const char* CompressorName(Compressor c);

/// The most bytes one compressed byte can decompress to with @p c (1 without compression).
std::uint64_t MaxRatio(Compressor c);

/// Saturating arithmetic: a hostile count must not wrap around to a small one.
std::uint64_t MulSat(std::uint64_t a, std::uint64_t b);
std::uint64_t AddSat(std::uint64_t a, std::uint64_t b);

/// A non-negative decimal integer, the whole (trimmed) text; VTK's attribute parser would read
/// "12abc" or "1e15" as their leading digits.
bool ParseUnsigned(const std::string& text, std::uint64_t& value);
bool ParseSigned(const std::string& text, long long& value);

/// The attribute @p name of @p e, when there is one.
std::optional<std::string> Attribute(vtkXMLDataElement* e, const char* name);

/// The elements nested in @p parent, only those named @p name when given.
std::vector<vtkXMLDataElement*> Children(vtkXMLDataElement* parent, const char* name = nullptr);

/// A file parsed the way VTK's XML readers parse it, with the settings every binary array is
/// read with (set from the root element by the checks) and the bytes counted so far.
class File
{
public:
  /// Parses @p path with vtkXMLDataParser; throws std::runtime_error on malformed markup.
  explicit File(const std::string& path);

  [[noreturn]] void Fail(const std::string& what) const;

  vtkXMLDataElement* Root() const;

  std::string path;
  std::uint64_t size = 0;
  std::ifstream in;

  // <AppendedData>: VTK reads an array at offset N from appendedBegin + N, raw or base64.
  bool appended = false;
  bool appendedRaw = false;
  std::uint64_t appendedBegin = 0;

  Compressor compressor = Compressor::None;
  std::uint64_t headerSize = 4; // bytes per size-header word (header_type)
  bool bigEndian = false;
  std::uint64_t budget = 0; // most bytes all arrays together can hold (file size x MaxRatio)
  std::uint64_t used = 0;   // bytes the arrays checked so far hold

private:
  vtkSmartPointer<vtkXMLDataParser> parser; // owns the element tree
};

/// The one <name> child of @p parent, or null; two are refused (which one VTK uses differs).
vtkXMLDataElement* OnlyChild(const File& f, vtkXMLDataElement* parent, const char* name, const std::string& where);

/// The first <DataArray> named @p name in @p parent, the one VTK reads for cells.
vtkXMLDataElement* FindNamedArray(vtkXMLDataElement* parent, const char* name);

/// A Piece's count attribute: an integer no larger than the file can hold.
std::uint64_t Count(const File& f, vtkXMLDataElement* e, const char* name, bool required, const std::string& where);

struct ArrayType
{
  const char* name;
  std::uint64_t size; // bytes per value
  char kind;          // 'i' signed, 'u' unsigned, 'f' floating point, 's' string (bytes)
};

/// A <DataArray> (or <Array>) with its attributes checked.
struct Array
{
  vtkXMLDataElement* element = nullptr;
  std::string label; // for messages: "piece 0 <PointData> array 'Normals'"
  const ArrayType* type = nullptr;
  std::uint64_t components = 1;
  bool ascii = false;
  bool appended = false;
};

/// How many values an array must hold, and why (for the message when it does not).
struct Expected
{
  std::uint64_t values = 0;
  std::string why;
};

/// The attributes of @p e, checked; @p label starts every message about it.
Array Describe(const File& f, vtkXMLDataElement* e, const std::string& label);

/// Checks the data of @p a before VTK reads them: the size header, the bytes present, and the
/// value count when known (@p expected); counts them towards the file's budget.
void CheckData(File& f, const Array& a, const Expected* expected);

/// Hands the values of an integer array with one component (offsets, connectivity, types,
/// faces) to @p visit in order, a run of them at a time, checked as CheckData does; there must be
/// exactly @p expected of them. Streams: no copy of the array is made.
void ForEachInteger(
  File& f, const Array& a, const Expected& expected, const std::function<void(const long long*, std::size_t)>& visit);

/// ForEachInteger's values, kept.
std::vector<long long> Integers(File& f, const Array& a, const Expected& expected);

}
}
}

#endif
