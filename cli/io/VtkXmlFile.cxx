// SPDX-License-Identifier: BSD-3-Clause
#include "VtkXmlFile.h"

#include "Bytes.h"
#include "Text.h"

#include "vtkBase64InputStream.h"
#include "vtkDataCompressor.h"
#include "vtkInputStream.h"
#include "vtkLZ4DataCompressor.h"
#include "vtkLZMADataCompressor.h"
#include "vtkObjectFactory.h"
#include "vtkXMLDataElement.h"
#include "vtkXMLDataParser.h"
#include "vtkZLibDataCompressor.h"
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

// Where an array's encoded data start, and whether VTK decodes them as base64 or reads them raw.
struct Stream
{
  std::uint64_t begin = 0;
  bool base64 = true;
};

// Most bytes @p s can decode to.
std::uint64_t Capacity(const File& f, const Stream& s)
{
  const std::uint64_t n = f.size > s.begin ? f.size - s.begin : 0;
  return s.base64 ? n / 4 * 3 : n;
}

// The stream VTK's parser reads @p s with, started at its first byte.
vtkSmartPointer<vtkInputStream> Open(File& f, const Stream& s)
{
  vtkSmartPointer<vtkInputStream> stream;
  if (s.base64)
  {
    stream = vtkSmartPointer<vtkBase64InputStream>::New();
  }
  else
  {
    stream = vtkSmartPointer<vtkInputStream>::New();
  }
  f.in.clear();
  f.in.seekg(static_cast<std::streamoff>(s.begin));
  stream->SetStream(&f.in);
  stream->StartReading();
  return stream;
}

// Reads up to @p count bytes from @p stream and returns how many it got: fewer when the file
// ends or, in base64, a character is not base64 or padding ends the text early. Appends them to
// @p out when given. Reads in pieces: @p count comes from a size header, which may promise far
// more than the file holds.
std::uint64_t Read(vtkInputStream* stream, std::uint64_t count, std::vector<unsigned char>* out)
{
  constexpr std::uint64_t piece = 1 << 16;
  std::vector<unsigned char> scratch;
  std::vector<unsigned char>& buffer = out ? *out : scratch;
  std::uint64_t n = 0;
  while (n < count)
  {
    const std::size_t want = static_cast<std::size_t>(std::min(count - n, piece));
    const std::size_t at = out ? buffer.size() : 0;
    buffer.resize(at + want);
    const std::size_t got = stream->Read(buffer.data() + at, want);
    buffer.resize(at + got);
    n += got;
    if (got < want)
    {
      break;
    }
  }
  return n;
}

// Word @p index of a size header.
std::uint64_t Word(const std::vector<unsigned char>& bytes, std::size_t index, std::uint64_t size, bool bigEndian)
{
  return LoadUnsigned(bytes.data() + index * size, static_cast<std::size_t>(size), bigEndian);
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

// Positions the file after the first '>' that follows the '<' of @p a's element: VTK's parser
// (vtkXMLDataParser::SeekInlineDataPosition) reads inline data from there, past white space.
void SeekInlineData(File& f, const Array& a)
{
  f.in.clear();
  f.in.seekg(static_cast<std::streamoff>(a.element->GetXMLByteIndex()));
  f.in.ignore(std::numeric_limits<std::streamsize>::max(), '>');
}

// The text of an ASCII array's inline data, up to the next '<' (no number reads past it).
std::string InlineText(File& f, const Array& a)
{
  SeekInlineData(f, a);
  std::string text;
  std::getline(f.in, text, '<');
  return text;
}

// Where the binary data of @p a start: inline, or in the appended data at its offset.
Stream Locate(File& f, const Array& a)
{
  Stream s;
  if (!a.appended)
  {
    SeekInlineData(f, a);
    int c = f.in.peek();
    while (c != std::char_traits<char>::eof() && std::isspace(c))
    {
      f.in.get();
      c = f.in.peek();
    }
    s.begin = c == std::char_traits<char>::eof() ? f.size : static_cast<std::uint64_t>(f.in.tellg());
    return s;
  }
  if (!f.appended)
  {
    f.Fail(a.label + ": format=\"appended\" but the file has no <AppendedData>");
  }
  const std::string text = *Attribute(a.element, "offset");
  std::uint64_t offset = 0;
  if (!ParseUnsigned(text, offset))
  {
    f.Fail(a.label + ": offset=\"" + text + "\" is not a non-negative integer");
  }
  const std::uint64_t length = f.size - f.appendedBegin;
  if (offset >= length)
  {
    f.Fail(a.label + ": offset " + text + " is past the end of the appended data (" + std::to_string(length) +
      " bytes)");
  }
  s.begin = f.appendedBegin + offset;
  s.base64 = !f.appendedRaw;
  return s;
}

// Visits the words of an ASCII array's inline text that VTK would read as its values (it stops
// at the first word it cannot parse as a value of the array's type) until @p visit returns
// false; returns how many it visited.
template <class Visit>
std::uint64_t AsciiValues(File& f, const Array& a, Visit&& visit)
{
  std::istringstream words(InlineText(f, a));
  std::uint64_t count = 0;
  std::string w;
  while (words >> w)
  {
    long long i = 0;
    double d = 0.0;
    if ((a.type->kind == 'f' ? !ParseDouble(w, d) : !ParseSigned(w, i)) || !visit(w))
    {
      break;
    }
    ++count;
  }
  return count;
}

// An array's binary size header, checked against itself and the bytes present.
struct SizeHeader
{
  std::uint64_t bytes = 0;           // decompressed size
  std::vector<std::uint64_t> blocks; // compressed block sizes (compressed files)
  std::uint64_t blockSize = 0;
  std::uint64_t lastBlockSize = 0; // 0: the last block is full
  std::uint64_t compressed = 0;    // sum of blocks
  Stream data;                     // compressed: the blocks; else header and data together
};

// The decompressed size of block @p i of @p count.
std::uint64_t BlockBytes(const SizeHeader& h, std::size_t i, std::size_t count)
{
  return i + 1 == count && h.lastBlockSize != 0 ? h.lastBlockSize : h.blockSize;
}

// Uncompressed: one word, the byte count, then the bytes, in one stream.
SizeHeader ReadPlainHeader(File& f, const Array& a, const Stream& s)
{
  SizeHeader h;
  const vtkSmartPointer<vtkInputStream> stream = Open(f, s);
  std::vector<unsigned char> word;
  if (Read(stream, f.headerSize, &word) < f.headerSize)
  {
    f.Fail(a.label + ": truncated: the data end (or stop being " + (s.base64 ? "base64" : "bytes") +
      ") inside the size header");
  }
  h.bytes = Word(word, 0, f.headerSize, f.bigEndian);
  h.data = s;
  // Raw bytes are there when the file is long enough; base64 text must also decode.
  const std::uint64_t room = Capacity(f, s) - f.headerSize;
  const std::uint64_t got = h.bytes > room ? room : s.base64 ? Read(stream, h.bytes, nullptr) : h.bytes;
  if (got < h.bytes)
  {
    f.Fail(a.label + ": truncated: the size header promises " + std::to_string(h.bytes) + " bytes but only " +
      std::to_string(got) + " follow" +
      (s.base64 ? " (the base64 text ends or holds a character that is not base64)" : ""));
  }
  return h;
}

// Compressed: number of blocks, block size, size of the last block (0: full), then each block's
// compressed size; the blocks follow where VTK's parser continues after reading the header (in
// base64, a second text after the header's padding).
SizeHeader ReadCompressedHeader(File& f, const Array& a, const Stream& s)
{
  SizeHeader h;
  const std::uint64_t hs = f.headerSize;
  const vtkSmartPointer<vtkInputStream> stream = Open(f, s);
  std::vector<unsigned char> words;
  if (Read(stream, 3 * hs, &words) < 3 * hs)
  {
    f.Fail(a.label + ": truncated: the data end (or stop being base64) inside the compression header");
  }
  const std::uint64_t count = Word(words, 0, hs, f.bigEndian);
  h.blockSize = Word(words, 1, hs, f.bigEndian);
  h.lastBlockSize = Word(words, 2, hs, f.bigEndian);
  // VTK allocates the list of block sizes as the header says: refused before, when the file
  // cannot hold it.
  if (count > (Capacity(f, s) - 3 * hs) / hs)
  {
    f.Fail(a.label + ": the compression header lists " + std::to_string(count) +
      " blocks, more than the rest of the file has room for");
  }
  if (Read(stream, count * hs, &words) < count * hs)
  {
    f.Fail(a.label + ": truncated: the data end (or stop being base64) inside the list of " + std::to_string(count) +
      " compressed block sizes");
  }
  if (count == 0 && h.lastBlockSize != 0)
  {
    f.Fail(a.label + ": the compression header has no blocks but a last block of " + std::to_string(h.lastBlockSize) +
      " bytes");
  }
  if (count > 0 && h.blockSize == 0)
  {
    f.Fail(a.label + ": the compression header has a block size of 0");
  }
  if (h.lastBlockSize > h.blockSize)
  {
    f.Fail(a.label + ": the compression header's last block (" + std::to_string(h.lastBlockSize) +
      " bytes) is larger than its block size (" + std::to_string(h.blockSize) + ")");
  }
  const std::uint64_t ratio = MaxRatio(f.compressor);
  for (std::size_t i = 0; i < count; ++i)
  {
    h.blocks.push_back(Word(words, 3 + i, hs, f.bigEndian));
    const std::uint64_t size = BlockBytes(h, i, count);
    if (size > MulSat(h.blocks.back(), ratio))
    {
      f.Fail(a.label + ": compressed block " + std::to_string(i) + " of " + std::to_string(h.blocks.back()) +
        " bytes cannot hold " + std::to_string(size) + " bytes (" + CompressorName(f.compressor) +
        " compresses at most " + std::to_string(ratio) + ":1)");
    }
    h.compressed = AddSat(h.compressed, h.blocks.back());
    h.bytes = AddSat(h.bytes, size);
  }
  h.data = Stream{ static_cast<std::uint64_t>(f.in.tellg()), s.base64 };
  const std::uint64_t room = Capacity(f, h.data);
  const std::uint64_t got = h.compressed > room ? room
    : s.base64                                  ? Read(Open(f, h.data), h.compressed, nullptr)
                                                : h.compressed;
  if (got < h.compressed)
  {
    f.Fail(a.label + ": truncated: the compressed blocks add up to " + std::to_string(h.compressed) +
      " bytes but only " + std::to_string(got) + " follow" +
      (s.base64 ? " (the base64 text ends or holds a character that is not base64)" : ""));
  }
  return h;
}

// Counts @p bytes more towards the budget: arrays may share their appended data, so each one
// fitting is not enough, all of them together must.
void Spend(File& f, const Array& a, std::uint64_t bytes)
{
  f.used = AddSat(f.used, bytes);
  if (f.used > f.budget)
  {
    f.Fail(a.label + ": the arrays up to this one hold " + std::to_string(f.used) + " bytes, more than a " +
      std::to_string(f.size) + "-byte file can hold (" + CompressorName(f.compressor) + ")");
  }
}

// CheckData, returning the size header (empty for ASCII data).
SizeHeader CheckSizes(File& f, const Array& a, const Expected* expected)
{
  const bool strings = a.type->kind == 's'; // variable length: at least one byte (its end) per string
  if (a.ascii)
  {
    const std::uint64_t present = AsciiValues(f, a, [](const std::string&) { return true; });
    if (expected && present < expected->values)
    {
      f.Fail(a.label + ": " + std::to_string(present) + " ASCII values, expected " + (strings ? "at least " : "") +
        std::to_string(expected->values) + " (" + expected->why + ")");
    }
    Spend(f, a, MulSat(expected ? expected->values : present, a.type->size));
    return SizeHeader();
  }
  const Stream s = Locate(f, a);
  const SizeHeader h = f.compressor == Compressor::None ? ReadPlainHeader(f, a, s) : ReadCompressedHeader(f, a, s);
  const std::uint64_t need = expected ? MulSat(expected->values, a.type->size) : 0;
  if (expected && (strings ? h.bytes < need : h.bytes != need))
  {
    f.Fail(a.label + ": its size header says " + std::to_string(h.bytes) + " bytes, expected " +
      (strings ? "at least " : "") + std::to_string(need) + " (" + expected->why + " x " +
      std::to_string(a.type->size) + "-byte " + a.type->name + ")");
  }
  Spend(f, a, h.bytes);
  return h;
}

vtkSmartPointer<vtkDataCompressor> NewCompressor(Compressor c)
{
  switch (c)
  {
    case Compressor::ZLib:
      return vtkSmartPointer<vtkZLibDataCompressor>::New();
    case Compressor::LZ4:
      return vtkSmartPointer<vtkLZ4DataCompressor>::New();
    case Compressor::LZMA:
      return vtkSmartPointer<vtkLZMADataCompressor>::New();
    case Compressor::None:
      break;
  }
  return nullptr;
}

// Hands the decoded bytes of a checked binary array (the cell arrays, whose values are checked)
// to @p sink piece by piece: one compressed block at a time, or 1 MiB at a time without
// compression, so that checking a large cell array needs no copy of it (a copy took as long as
// VTK's whole read of a 10^7-point cloud). vtkXMLDataParser's ReadInlineData/ReadAppendedData
// would decode them too, but they read the size header again with nothing checked (allocating
// what it claims) and accept a block that decompresses to fewer bytes than it should (VTK's reader
// then keeps uninitialized values): here every block must decompress to exactly its size.
void DecodeInPieces(File& f, const Array& a, const SizeHeader& h,
  const std::function<void(const unsigned char*, std::size_t)>& sink)
{
  const vtkSmartPointer<vtkInputStream> stream = Open(f, h.data);
  std::vector<unsigned char> piece;
  if (f.compressor == Compressor::None)
  {
    Read(stream, f.headerSize, nullptr);
    constexpr std::uint64_t pieceSize = 1 << 20;
    for (std::uint64_t left = h.bytes; left > 0;)
    {
      const std::uint64_t want = std::min(left, pieceSize);
      piece.clear();
      Read(stream, want, &piece);
      sink(piece.data(), piece.size());
      left -= want;
    }
    return;
  }
  const vtkSmartPointer<vtkDataCompressor> compressor = NewCompressor(f.compressor);
  std::vector<unsigned char> packed;
  for (std::size_t i = 0; i < h.blocks.size(); ++i)
  {
    packed.clear();
    Read(stream, h.blocks[i], &packed);
    const std::size_t size = BlockBytes(h, i, h.blocks.size());
    piece.resize(size);
    if (compressor->Uncompress(packed.data(), packed.size(), piece.data(), size) != size)
    {
      f.Fail(a.label + ": compressed block " + std::to_string(i) + " is corrupt (it does not decompress to its " +
        std::to_string(size) + " bytes)");
    }
    sink(piece.data(), size);
  }
}

// The @p count integers of Size bytes each at @p p; an unsigned value beyond the largest long
// long becomes that largest one (it fails every range check). The size known at compile time
// makes the loop several times faster, which a 10^7-point cloud's vertex cells notice.
template <std::size_t Size>
void IntegersAt(const unsigned char* p, std::size_t count, const ArrayType& t, bool bigEndian, long long* out)
{
  for (std::size_t i = 0; i < count; ++i)
  {
    const unsigned char* v = p + i * Size;
    out[i] = t.kind == 'i' ? LoadSigned(v, Size, bigEndian)
                           : static_cast<long long>(std::min<std::uint64_t>(
                               LoadUnsigned(v, Size, bigEndian), std::numeric_limits<long long>::max()));
  }
}

void IntegersAt(const unsigned char* p, std::size_t count, const ArrayType& t, bool bigEndian, long long* out)
{
  switch (t.size)
  {
    case 1:
      return IntegersAt<1>(p, count, t, bigEndian, out);
    case 2:
      return IntegersAt<2>(p, count, t, bigEndian, out);
    case 4:
      return IntegersAt<4>(p, count, t, bigEndian, out);
    default:
      return IntegersAt<8>(p, count, t, bigEndian, out);
  }
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

void CheckData(File& f, const Array& a, const Expected* expected)
{
  CheckSizes(f, a, expected);
}

void ForEachInteger(File& f, const Array& a, const Expected& expected,
  const std::function<void(const long long*, std::size_t)>& visit)
{
  if (a.type->kind != 'i' && a.type->kind != 'u')
  {
    f.Fail(a.label + ": must be an integer array, not " + a.type->name);
  }
  if (a.components != 1)
  {
    f.Fail(a.label + ": must have one component");
  }
  const SizeHeader h = CheckSizes(f, a, &expected);
  std::uint64_t count = 0;
  if (a.ascii)
  {
    if (expected.values > 0)
    {
      AsciiValues(f, a, [&](const std::string& w) {
        long long v = 0;
        ParseSigned(w, v);
        visit(&v, 1);
        return ++count < expected.values;
      });
    }
    return;
  }
  // A value may straddle two pieces: its first bytes wait in `partial`.
  const std::size_t size = static_cast<std::size_t>(a.type->size);
  unsigned char partial[8];
  std::size_t pending = 0;
  std::vector<long long> values;
  DecodeInPieces(f, a, h, [&](const unsigned char* bytes, std::size_t n) {
    std::size_t at = 0;
    if (pending > 0)
    {
      const std::size_t take = std::min(size - pending, n);
      std::copy(bytes, bytes + take, partial + pending);
      pending += take;
      at = take;
      if (pending == size && count < expected.values)
      {
        long long v = 0;
        IntegersAt(partial, 1, *a.type, f.bigEndian, &v);
        visit(&v, 1);
        ++count;
      }
      pending = pending == size ? 0 : pending;
    }
    const std::size_t whole = static_cast<std::size_t>(std::min<std::uint64_t>((n - at) / size, expected.values - count));
    values.resize(whole);
    IntegersAt(bytes + at, whole, *a.type, f.bigEndian, values.data());
    visit(values.data(), whole);
    count += whole;
    at += whole * size;
    if (count < expected.values && at < n)
    {
      pending = n - at;
      std::copy(bytes + at, bytes + n, partial);
    }
  });
}

std::vector<long long> Integers(File& f, const Array& a, const Expected& expected)
{
  // Not reserved: expected.values is only trusted once ForEachInteger has checked the size header.
  std::vector<long long> values;
  ForEachInteger(f, a, expected, [&](const long long* v, std::size_t n) { values.insert(values.end(), v, v + n); });
  return values;
}

}
}
}
