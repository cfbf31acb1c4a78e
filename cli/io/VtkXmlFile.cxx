// SPDX-License-Identifier: BSD-3-Clause
#include "VtkXmlFile.h"

#include "Bytes.h"
#include "Text.h"

#include "vtkObjectFactory.h"
#include "vtkXMLDataElement.h"
#include "vtkXMLDataParser.h"
#include "vtk_expat.h"

#include <algorithm>
#include <cctype>
#include <cstring>
#include <functional>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace pss_cli
{
namespace io
{
namespace vtkxml
{

namespace
{

// vtkXMLDataParser exactly as VTK's XML readers run it (expat, stopping at <AppendedData>), except
// that expat's error is kept for the exception instead of printed, and says which element a file
// cut off ends inside.
class DataParser : public vtkXMLDataParser
{
public:
  static DataParser* New();
  vtkTypeMacro(DataParser, vtkXMLDataParser);

  // vtkXMLDataParser::Parse() adds its own check of byte_order and header_type, which prints
  // VTK's error; the root's checks in VtkXml.cxx refuse the same values with the file's name.
  int Parse() override { return this->vtkXMLParser::Parse(); }

  std::string error;

protected:
  using vtkXMLDataParser::Parse; // the string overloads, which vtkXMLDataParser refuses

  // vtkXMLParser::Parse() tells expat about the end of the input after this returns: an error
  // reported then means the document is incomplete.
  int ParseXML() override
  {
    auto* xml = static_cast<XML_Parser>(this->Parser);
    XML_SetStartDoctypeDeclHandler(xml, &RefuseDoctype);
    XML_SetStartCdataSectionHandler(xml, &RefuseCdata);
    const int ok = this->Superclass::ParseXML();
    this->atEnd = true;
    return ok;
  }

  void ReportXmlParseError() override
  {
    auto* xml = static_cast<XML_Parser>(this->Parser);
    const std::string line = "line " + std::to_string(XML_GetCurrentLineNumber(xml)) + ": ";
    if (this->unsupported)
    {
      this->error = line + "unsupported markup (a DOCTYPE or CDATA section)";
    }
    else if (this->atEnd && this->NumberOfOpenElements > 0)
    {
      const char* open = this->OpenElements[this->NumberOfOpenElements - 1]->GetName();
      this->error = line + "<" + open + "> is not closed (the file is cut off?)";
    }
    else
    {
      this->error = line + XML_ErrorString(XML_GetErrorCode(xml));
    }
  }

private:
  // VTK's writers write neither; a DOCTYPE can define entities that expand far beyond the file,
  // and a CDATA section is not where VTK's readers look for data. Expat calls these with the
  // vtkXMLParser as its user data.
  static void XMLCALL RefuseDoctype(void* parser, const XML_Char*, const XML_Char*, const XML_Char*, int)
  {
    RefuseCdata(parser);
  }
  static void XMLCALL RefuseCdata(void* parser)
  {
    auto* self = static_cast<DataParser*>(static_cast<vtkXMLParser*>(parser));
    self->unsupported = true;
    XML_StopParser(static_cast<XML_Parser>(self->Parser), XML_FALSE);
  }

  bool atEnd = false;
  bool unsupported = false;
};
vtkStandardNewMacro(DataParser);

// The byte at @p offset of the file, or -1 past its end.
int ByteAt(File& f, std::uint64_t offset)
{
  f.in.clear();
  f.in.seekg(static_cast<std::streamoff>(offset));
  return f.in.get();
}

// "line N: " of the start tag of @p e, for messages.
std::string LineOf(File& f, vtkXMLDataElement* e)
{
  f.in.clear();
  f.in.seekg(0);
  std::uint64_t line = 1;
  for (vtkTypeInt64 i = 0; i < e->GetXMLByteIndex() && f.in; ++i)
  {
    line += f.in.get() == '\n' ? 1 : 0;
  }
  return "line " + std::to_string(line) + ": ";
}

const ArrayType* LookUpArrayType(const std::string& name)
{
  static const ArrayType types[] = { { "Int8", 1, 'i' }, { "UInt8", 1, 'u' }, { "Int16", 2, 'i' },
    { "UInt16", 2, 'u' }, { "Int32", 4, 'i' }, { "UInt32", 4, 'u' }, { "Int64", 8, 'i' }, { "UInt64", 8, 'u' },
    { "Float32", 4, 'f' }, { "Float64", 8, 'f' }, { "String", 1, 's' } };
  for (const ArrayType& t : types)
  {
    if (name == t.name)
    {
      return &t;
    }
  }
  return nullptr;
}

} // namespace

const char* CompressorName(Compressor c)
{
  switch (c)
  {
    case Compressor::ZLib:
      return "vtkZLibDataCompressor";
    case Compressor::LZ4:
      return "vtkLZ4DataCompressor";
    case Compressor::LZMA:
      return "vtkLZMADataCompressor";
    case Compressor::None:
      break;
  }
  return "no compressor";
}

// Deflate codes a 258-byte match in 2 bits at best: 1032:1. An LZ4 sequence needs one more byte
// for every 255 bytes of match length: < 255:1. LZMA2 (xz, what vtkLZMADataCompressor writes)
// codes a 273-byte repeat in about 14 binary decisions whose probability is at most 2017/2048
// (11-bit probabilities adapted by 1/32), 0.31 bit, i.e. ~7000:1, less its chunk headers
// (`xz -9e` reaches 6870:1 on zeros); 8192 keeps a margin.
std::uint64_t MaxRatio(Compressor c)
{
  switch (c)
  {
    case Compressor::ZLib:
      return 1032;
    case Compressor::LZ4:
      return 255;
    case Compressor::LZMA:
      return 8192;
    case Compressor::None:
      break;
  }
  return 1;
}

std::uint64_t MulSat(std::uint64_t a, std::uint64_t b)
{
  std::uint64_t r = 0;
  return __builtin_mul_overflow(a, b, &r) ? std::numeric_limits<std::uint64_t>::max() : r;
}

std::uint64_t AddSat(std::uint64_t a, std::uint64_t b)
{
  std::uint64_t r = 0;
  return __builtin_add_overflow(a, b, &r) ? std::numeric_limits<std::uint64_t>::max() : r;
}

bool ParseUnsigned(const std::string& text, std::uint64_t& value)
{
  const std::string t = Trim(text);
  if (t.empty() || t.size() > 18 ||
    !std::all_of(t.begin(), t.end(), [](unsigned char c) { return std::isdigit(c) != 0; }))
  {
    return false;
  }
  value = std::stoull(t);
  return true;
}

bool ParseSigned(const std::string& text, long long& value)
{
  const std::string t = Trim(text);
  const bool negative = !t.empty() && t[0] == '-';
  std::uint64_t magnitude = 0;
  if (!ParseUnsigned(negative ? t.substr(1) : t, magnitude) || (negative && t.size() == 1))
  {
    return false;
  }
  value = negative ? -static_cast<long long>(magnitude) : static_cast<long long>(magnitude);
  return true;
}

std::optional<std::string> Attribute(vtkXMLDataElement* e, const char* name)
{
  const char* value = e->GetAttribute(name);
  return value ? std::optional<std::string>(value) : std::nullopt;
}

std::vector<vtkXMLDataElement*> Children(vtkXMLDataElement* parent, const char* name)
{
  std::vector<vtkXMLDataElement*> out;
  for (int i = 0; i < parent->GetNumberOfNestedElements(); ++i)
  {
    vtkXMLDataElement* child = parent->GetNestedElement(i);
    if (!name || std::strcmp(child->GetName(), name) == 0)
    {
      out.push_back(child);
    }
  }
  return out;
}

File::File(const std::string& p)
  : path(p)
  , in(p, std::ios::binary)
{
  in.seekg(0, std::ios::end);
  size = in ? static_cast<std::uint64_t>(in.tellg()) : 0;
  in.seekg(0);
  auto reader = vtkSmartPointer<DataParser>::New();
  parser = reader;
  reader->SetStream(&in);
  // The readers read array data from the file, not from the element tree.
  reader->SetIgnoreCharacterData(1);
  if (!reader->Parse() || !reader->GetRootElement())
  {
    Fail(reader->error.empty() ? "not well-formed XML" : reader->error);
  }
  // vtkXMLDataParser found the appended data after the '_' that follows <AppendedData ...>, where
  // VTK reads them from; without the '_' it would start one byte earlier, at whatever is there.
  const std::vector<vtkXMLDataElement*> sections = Children(Root(), "AppendedData");
  if (sections.empty())
  {
    return;
  }
  const std::optional<std::string> encoding = Attribute(sections[0], "encoding");
  if (encoding && *encoding != "raw" && *encoding != "base64")
  {
    Fail(LineOf(*this, sections[0]) + "<AppendedData encoding=\"" + *encoding + "\">: expected raw or base64");
  }
  const vtkTypeInt64 position = reader->GetAppendedDataPosition();
  const std::uint64_t begin = position > 0 ? static_cast<std::uint64_t>(position) : 0;
  if (begin == 0 || begin > size || ByteAt(*this, begin - 1) != '_')
  {
    Fail(LineOf(*this, sections[0]) + "the appended data do not start with '_'");
  }
  appended = true;
  appendedRaw = encoding && *encoding == "raw";
  appendedBegin = begin;
}

void File::Fail(const std::string& what) const
{
  throw std::runtime_error(path + ": not a VTK XML file pss can read safely: " + what);
}

vtkXMLDataElement* File::Root() const
{
  return parser->GetRootElement();
}

vtkXMLDataElement* OnlyChild(const File& f, vtkXMLDataElement* parent, const char* name, const std::string& where)
{
  const std::vector<vtkXMLDataElement*> found = Children(parent, name);
  if (found.size() > 1)
  {
    f.Fail(where + ": more than one <" + name + ">");
  }
  return found.empty() ? nullptr : found[0];
}

vtkXMLDataElement* FindNamedArray(vtkXMLDataElement* parent, const char* name)
{
  for (vtkXMLDataElement* child : Children(parent, "DataArray"))
  {
    const char* n = child->GetAttribute("Name");
    if (n && std::strcmp(n, name) == 0)
    {
      return child;
    }
  }
  return nullptr;
}

std::uint64_t Count(const File& f, vtkXMLDataElement* e, const char* name, bool required, const std::string& where)
{
  const std::optional<std::string> text = Attribute(e, name);
  if (!text)
  {
    if (required)
    {
      f.Fail(where + ": no " + name + " attribute");
    }
    return 0;
  }
  std::uint64_t n = 0;
  if (!ParseUnsigned(*text, n))
  {
    f.Fail(where + ": " + name + "=\"" + *text + "\" is not a non-negative integer");
  }
  if (n > f.budget)
  {
    f.Fail(where + ": " + name + "=\"" + *text + "\" is more than a " + std::to_string(f.size) +
      "-byte file can hold");
  }
  return n;
}

Array Describe(const File& f, vtkXMLDataElement* e, const std::string& label)
{
  // Most components an array may have: VTK loops over them for component names before reading.
  constexpr std::uint64_t maxComponents = 65535;
  Array a;
  a.element = e;
  const std::optional<std::string> name = Attribute(e, "Name");
  a.label = label + (name ? " '" + *name + "'" : std::string());
  if (std::strcmp(e->GetName(), "DataArray") != 0 && std::strcmp(e->GetName(), "Array") != 0)
  {
    f.Fail(a.label + ": <" + e->GetName() + "> where a <DataArray> belongs");
  }
  const std::optional<std::string> type = Attribute(e, "type");
  a.type = type ? LookUpArrayType(*type) : nullptr;
  if (!a.type)
  {
    f.Fail(a.label + ": " + (type ? "unknown type '" + *type + "'" : std::string("no type")) +
      " (known: Int8, UInt8, Int16, UInt16, Int32, UInt32, Int64, UInt64, Float32, Float64, String)");
  }
  if (const std::optional<std::string> nc = Attribute(e, "NumberOfComponents"))
  {
    if (!ParseUnsigned(*nc, a.components) || a.components < 1 || a.components > maxComponents)
    {
      f.Fail(a.label + ": NumberOfComponents=\"" + *nc + "\" is not an integer in [1, " +
        std::to_string(maxComponents) + "]");
    }
  }
  if (Attribute(e, "TimeStep"))
  {
    f.Fail(a.label + ": arrays with a TimeStep are not supported");
  }
  const std::optional<std::string> format = Attribute(e, "format");
  if (!format || (*format != "ascii" && *format != "binary" && *format != "appended"))
  {
    f.Fail(a.label + ": format=\"" + format.value_or("") + "\", expected ascii, binary or appended");
  }
  a.ascii = *format == "ascii";
  a.appended = *format == "appended";
  // VTK reads appended data whenever there is an offset, whatever the format says.
  if (a.appended != Attribute(e, "offset").has_value())
  {
    f.Fail(a.label +
      (a.appended ? ": format=\"appended\" without an offset" : ": an offset but format=\"" + *format + "\""));
  }
  // VTK rebuilds quadrature-scheme dictionaries from sizes written in the file, unchecked.
  for (vtkXMLDataElement* key : Children(e, "InformationKey"))
  {
    if (Attribute(key, "location").value_or("") == "vtkQuadratureSchemeDefinition")
    {
      f.Fail(a.label + ": quadrature-scheme information keys are not supported");
    }
  }
  return a;
}
}
}
}
