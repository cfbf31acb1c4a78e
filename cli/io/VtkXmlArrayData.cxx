// SPDX-License-Identifier: BSD-3-Clause
// The data of an array element of a VTK XML file: where they start (inline or appended, raw or
// base64), their size headers and blocks (compressed or not), checked against the file and the
// budget before anything is allocated, and decoded as integers. (VtkXmlFile.cxx parses the file.)
#include "VtkXmlFile.h"

#include "Bytes.h"
#include "Text.h"

#include "vtkBase64InputStream.h"
#include "vtkDataCompressor.h"
#include "vtkInputStream.h"
#include "vtkLZ4DataCompressor.h"
#include "vtkLZMADataCompressor.h"
#include "vtkXMLDataElement.h"
#include "vtkZLibDataCompressor.h"

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
