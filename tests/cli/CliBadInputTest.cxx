// SPDX-License-Identifier: BSD-3-Clause
// The pss tool on unreadable, malformed and absurd input, as the bad-input table
// (docs/bad-input.md) states it: every case exits 1 with a message that says what is wrong (never
// a crash, which RunCommand reports as exit -1), and nothing is written.
#include "CliTestUtilities.h"

#include "vtkNew.h"
#include "vtkSmartPointer.h"
#include "vtkXMLGenericDataObjectReader.h"
#include "vtkXMLPolyDataWriter.h"
#include "vtkXMLUnstructuredGridWriter.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <utility>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

using namespace pss_cli_test;

namespace
{

std::string Write(const std::string& name, const std::string& contents)
{
  const std::string path = TempPath(name);
  std::ofstream(path, std::ios::binary) << contents;
  return path;
}

// Runs `pss project INPUT -o OUTPUT` and expects exit 1, @p message in what it printed, and no output.
void ExpectRejected(const std::string& input, const std::string& message, const std::string& extra = "")
{
  const std::string output = TempPath("rejected-out.vtp");
  std::remove(output.c_str());
  const CommandResult r = RunCommand(Pss() + " project " + input + " " + extra + " -o " + output);
  EXPECT_EQ(r.exitCode, 1) << input << ": " << r.output;
  EXPECT_NE(r.output.find(message), std::string::npos) << input << ": expected \"" << message << "\" in: " << r.output;
  EXPECT_FALSE(std::ifstream(output).good()) << input << ": an output was written";
}

const char* const kPlyHeader = "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                               "property float z\n";

std::string BinaryPly(int declared, int written)
{
  std::string s = "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(declared) +
    "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  for (int i = 0; i < 3 * written; ++i)
  {
    const float v = 0.1f * static_cast<float>(i);
    s.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  return s;
}

std::string ReadAll(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// A 12-point cloud from pss generate, rewritten by VTK with inline base64 data (pss itself writes
// appended raw data, which MalformedAppendedXml covers): the text the tests below cut and edit.
std::string Generated(const std::string& name, const std::string& compression)
{
  const std::string appended = TempPath("appended-" + name);
  const CommandResult r = RunCommand(Pss() + " generate --scene noisy-curve --count 12 --compression " + compression +
    " -o " + appended);
  EXPECT_EQ(r.exitCode, 0) << r.output;
  vtkNew<vtkXMLGenericDataObjectReader> reader;
  reader->SetFileName(appended.c_str());
  reader->Update();
  const bool poly = name.size() > 4 && name.compare(name.size() - 4, 4, ".vtp") == 0;
  vtkSmartPointer<vtkXMLWriter> writer;
  if (poly)
  {
    writer = vtkSmartPointer<vtkXMLPolyDataWriter>::New();
  }
  else
  {
    writer = vtkSmartPointer<vtkXMLUnstructuredGridWriter>::New();
  }
  const std::string path = TempPath(name);
  writer->SetFileName(path.c_str());
  writer->SetInputDataObject(reader->GetOutputDataObject(0));
  writer->SetDataModeToBinary();
  if (compression == "lz4")
  {
    writer->SetCompressorTypeToLZ4();
  }
  else if (compression == "zlib")
  {
    writer->SetCompressorTypeToZLib();
  }
  else
  {
    writer->SetCompressorTypeToNone();
  }
  EXPECT_EQ(writer->Write(), 1) << path;
  return ReadAll(path);
}

// @p s with the first @p from replaced by @p to (which must be there).
std::string Replaced(std::string s, const std::string& from, const std::string& to)
{
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << "'" << from << "' not in the generated file";
  return at == std::string::npos ? s : s.replace(at, from.size(), to);
}

// @p s with the second half of the base64 text of its Points array cut off.
std::string TruncatedPoints(std::string s)
{
  const auto tag = s.find("Name=\"Points\"");
  const auto begin = s.find_first_not_of(" \n", s.find('>', tag) + 1);
  const auto end = s.find_first_of("\n<", begin);
  EXPECT_NE(tag, std::string::npos);
  return s.erase(begin + (end - begin) / 2, end - begin - (end - begin) / 2);
}

// A polydata of 8 points on a line in appended raw data (a 4-byte size header, then 8 x 3 floats),
// its Points array at @p offset.
std::string AppendedVtp(const std::string& offset)
{
  std::string raw;
  auto put = [&raw](std::uint32_t bits) {
    for (int b = 0; b < 4; ++b)
    {
      raw += static_cast<char>((bits >> (8 * b)) & 0xFF);
    }
  };
  put(8 * 3 * 4);
  for (int i = 0; i < 8; ++i)
  {
    for (const float v : { 0.5f * static_cast<float>(i), 0.0f, 0.0f })
    {
      std::uint32_t bits = 0;
      std::memcpy(&bits, &v, sizeof bits);
      put(bits);
    }
  }
  return "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt32\">\n<PolyData>\n<Piece NumberOfPoints=\"8\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
         "NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n<Points>\n<DataArray type=\"Float32\" Name=\"Points\" "
         "NumberOfComponents=\"3\" format=\"appended\" offset=\"" +
    offset + "\"/>\n</Points>\n</Piece>\n</PolyData>\n<AppendedData encoding=\"raw\">\n_" + raw +
    "\n</AppendedData>\n</VTKFile>\n";
}

} // namespace

// Files that cannot be read at all: missing, a folder, an unknown extension.
TEST(CliBadInput, UnreadableFiles)
{
  ExpectRejected("/nonexistent/cloud.csv", "cannot open");
  ExpectRejected(PSS_BINARY_DIR, "unknown input format");
  ExpectRejected(Write("cloud.foo", "1 2 3\n"), "unknown input format '.foo'");
  ExpectRejected(Write("empty.xyz", ""), "empty");
}

// Text tables: the line that is wrong is named; a header wider than its rows once read past the
// last column (a segfault); a row of the wrong width, a non-number, a single column.
TEST(CliBadInput, MalformedTables)
{
  ExpectRejected(Write("wide-header.csv", "a,b,x,y\n1,2\n3,4\n"), ":2: the header names 4 columns, this row has 2");
  ExpectRejected(Write("narrow-header.csv", "x,y\n1,2,3\n"), ":2: the header names 2 columns, this row has 3");
  ExpectRejected(Write("ragged.xyz", "1 2 3\n4 5 6\n7 8\n"), ":3: expected 3 columns, found 2");
  ExpectRejected(Write("word.csv", "x,y,z\n1,2,3\n4,five,6\n"), ":3: not a row of numbers");
  ExpectRejected(Write("one-column.xyz", "1\n2\n"), ":1: need at least two columns");
  ExpectRejected(Write("binary.xyz", std::string("\x7f" "ELF\x02\x01\x01\0\0\0", 10)), ":1: not a row of numbers");
}

// PLY: VTK's reader aborted (assert) or crashed on each of these before pss checked them (the
// face index past the vertices and an element without properties: segfaults found by
// Fuzz.cli_input).
TEST(CliBadInput, MalformedPly)
{
  const std::string header = kPlyHeader;
  ExpectRejected(Write("no-end-header.ply", header + "0 0 0\n1 0 0\n0 1 0\n"), "unknown header line '0'");
  ExpectRejected(Write("truncated-header.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty flr\n"),
    "expected 'property TYPE NAME'");
  ExpectRejected(Write("blank-line.ply", header + "end_header\n0 0 0\n\n1 0 0\n0 1 0\n"), "missing or non-numeric");
  ExpectRejected(Write("short-body.ply", header + "end_header\n0 0 0\n1 0 0\n"), "the file ends after 2 of 3 'vertex' rows");
  ExpectRejected(Write("extra-value.ply", header + "end_header\n0 0 0 7\n1 0 0\n0 1 0\n"), "1 values too many");
  ExpectRejected(Write("huge-count.ply", BinaryPly(2000000000, 3)), "the file ends inside 'vertex' row 3");
  ExpectRejected(Write("truncated-binary.ply", BinaryPly(5, 4)), "the file ends inside 'vertex' row 4");
  ExpectRejected(Write("no-z.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n"),
    "no 'vertex' element with x, y and z");
  ExpectRejected(Write("list-x.ply",
                   "ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar float x\nproperty float y\n"
                   "property float z\nend_header\n1 0 0 0\n"),
    "property 'x' of element 'vertex' must not be a list");

  ExpectRejected(Write("face-index.ply", header + "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                                  "0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"),
    "vertex index 7.000000 outside [0, 3)");

  ExpectRejected(Write("element-without-properties.ply", header + "element face 0\nend_header\n0 0 0\n1 0 0\n0 1 0\n"),
    "element 'face' declares no properties");
  ExpectRejected(Write("face-without-indices.ply", header + "element face 1\nproperty list uchar int vertex_indicez\n"
                                                            "end_header\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"),
    "element 'face' has no 'vertex_indices'");

  ExpectRejected(Write("nul-in-header.ply", std::string("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\n"
                                                        "property float y\nproperty float z\nelement face 0\n"
                                                        "property list uchar int \0\0ndices\nend_header\n0 0 0\n",
                                              154)),
    "control character in the header");

  ExpectRejected(Write("no-final-newline.ply", header + "end_header\n0 0 0\n1 0 0\n0 1 0"), "ends without a line end");

  // A well-formed file still reads (binary, and ASCII with CRLF line ends).
  const CommandResult ok = RunCommand(Pss() + " project " + Write("good.ply", BinaryPly(5, 5)) + " --h 1 -o " +
    TempPath("good-ply.csv"));
  EXPECT_EQ(ok.exitCode, 0) << ok.output;
  const CommandResult crlf = RunCommand(Pss() + " project " +
    Write("crlf.ply", "ply\r\nformat ascii 1.0\r\nelement vertex 3\r\nproperty float x\r\nproperty float y\r\n"
                      "property float z\r\nend_header\r\n0 0 0\r\n1 0 0\r\n0 1 0\r\n") +
    " --h 1 -o " + TempPath("crlf-ply.csv"));
  EXPECT_EQ(crlf.exitCode, 0) << crlf.output;
}

// XML: not XML, cut off, and a valid file whose piece has no points.
TEST(CliBadInput, MalformedVtp)
{
  ExpectRejected(Write("garbage.vtp", "this is not XML\n"), "cannot read");
  ExpectRejected(Write("cut.vtp", "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\">\n<PolyData>\n<Piece "
                                  "NumberOfPoints=\"3\""),
    "is not closed (the file is cut off?)");
}

// Binary XML: VTK's readers trusted every count and size header, and allocated gigabytes or read
// outside their buffers on a corrupted one (Fuzz.cli_input); pss checks them first and names the
// array or attribute that is wrong.
TEST(CliBadInput, MalformedBinaryXml)
{
  const std::string plain = Generated("plain.vtp", "none");
  const std::string zlib = Generated("zlib.vtp", "zlib");
  const std::string grid = Generated("lz4.vtu", "lz4");

  // Truncated base64: the size header promises more bytes than the text holds.
  ExpectRejected(Write("truncated-plain.vtp", TruncatedPoints(plain)),
    "<Points> array 'Points': truncated: the size header promises 288 bytes but only");
  ExpectRejected(Write("truncated-zlib.vtp", TruncatedPoints(zlib)),
    "<Points> array 'Points': truncated: the compressed blocks add up to");
  ExpectRejected(Write("truncated-lz4.vtu", TruncatedPoints(grid)), "truncated: the compressed blocks add up to");

  // A size header that disagrees with NumberOfPoints (12 points of 3 Float64 are 288 bytes).
  ExpectRejected(Write("more-points.vtp", Replaced(plain, "NumberOfPoints=\"12\"", "NumberOfPoints=\"13\"")),
    "its size header says 288 bytes, expected 312 (NumberOfPoints 13 x 3 x 8-byte Float64)");
  ExpectRejected(Write("more-points-zlib.vtp", Replaced(zlib, "NumberOfPoints=\"12\"", "NumberOfPoints=\"11\"")),
    "its size header says 288 bytes, expected 264");

  // Absurd counts.
  ExpectRejected(
    Write("huge-count.vtp", Replaced(zlib, "NumberOfPoints=\"12\"", "NumberOfPoints=\"1000000000000000\"")),
    "NumberOfPoints=\"1000000000000000\" is more than a");
  ExpectRejected(Write("float-count.vtp", Replaced(zlib, "NumberOfPoints=\"12\"", "NumberOfPoints=\"1e15\"")),
    "NumberOfPoints=\"1e15\" is not a non-negative integer");
  ExpectRejected(Write("negative-cells.vtu", Replaced(grid, "NumberOfCells=\"12\"", "NumberOfCells=\"-12\"")),
    "NumberOfCells=\"-12\" is not a non-negative integer");
  // 2^29 + 1 compressed blocks in a 3 KB file: VTK allocated 4 GB for their sizes (the first
  // out-of-memory Fuzz.cli_input found).
  ExpectRejected(
    Write("block-count.vtp", Replaced(zlib, ">\n          AQAAAACAAAAgAQAA", ">\n          AQAAIACAAAAgAQAA")),
    "blocks, more than the rest of the file has room for");

  // Unknown compressor, header type, array type.
  ExpectRejected(Write("brotli.vtp", Replaced(zlib, "vtkZLibDataCompressor", "vtkBrotliDataCompressor")),
    "compressor=\"vtkBrotliDataCompressor\">: unknown compressor");
  ExpectRejected(Write("uint16-header.vtp", Replaced(zlib, "header_type=\"UInt32\"", "header_type=\"UInt16\"")),
    "header_type=\"UInt16\">: expected UInt32 or UInt64");
  ExpectRejected(
    Write("bad-type.vtp", Replaced(plain, "type=\"Float64\" Name=\"Points\"", "type=\"Float99\" Name=\"Points\"")),
    "unknown type 'Float99'");
}

// Cells: VTK sizes the connectivity by the last offset and indexes points with its entries.
TEST(CliBadInput, MalformedXmlCells)
{
  auto grid = [](const std::string& connectivity, const std::string& offsets, const std::string& types) {
    return "<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" byte_order=\"LittleEndian\">\n<UnstructuredGrid>\n"
           "<Piece NumberOfPoints=\"4\" NumberOfCells=\"2\">\n<Points>\n<DataArray type=\"Float32\" "
           "NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0 1 1 0</DataArray>\n</Points>\n<Cells>\n"
           "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">" +
      connectivity + "</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">" + offsets +
      "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">" + types +
      "</DataArray>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n</VTKFile>\n";
  };
  ExpectRejected(Write("cell-point.vtu", grid("0 1 2 1 3 7", "3 6", "5 5")), "entry 5 is point 7, outside [0, 4)");
  ExpectRejected(Write("cell-offsets.vtu", grid("0 1 2 1 3 2", "3 2", "5 5")), "is below the previous one");
  ExpectRejected(Write("cell-length.vtu", grid("0 1 2 1 3 2", "3 600000", "5 5")), "6 ASCII values, expected 600000");
  ExpectRejected(Write("cell-type.vtu", grid("0 1 2 1 3 2", "3 6", "5 99")), "cell 1 has the unknown type 99");
  const std::string cells = Write("cells.vtu", grid("0 1 2 1 3 2", "3 6", "5 5"));
  const CommandResult ok = RunCommand(Pss() + " project " + cells + " --h 1 -o " + TempPath("cells.csv"));
  EXPECT_EQ(ok.exitCode, 0) << ok.output;
}

// Appended data: an offset past the end of the <AppendedData> section; the same file with a
// correct offset reads.
TEST(CliBadInput, MalformedAppendedXml)
{
  ExpectRejected(Write("offset-past-end.vtp", AppendedVtp("4000")), "offset 4000 is past the end of the appended data");
  // At offset 16 the size header is the float 0.5 (0x3F000000 bytes).
  ExpectRejected(Write("offset-inside.vtp", AppendedVtp("16")), "truncated: the size header promises 1056964608 bytes");
  ExpectRejected(Write("offset-negative.vtp", AppendedVtp("-4")), "offset=\"-4\" is not a non-negative integer");
  const CommandResult ok = RunCommand(Pss() + " project " + Write("appended.vtp", AppendedVtp("0")) + " --h 1 -o " +
    TempPath("appended-out.csv"));
  EXPECT_EQ(ok.exitCode, 0) << ok.output;
}

// What pss and VTK write still reads: every compression, as .vtp, .vtu, and .vti (a sampled grid
// read back as the probe of another sample). 2000 points: their coordinates span two compressed
// blocks.
TEST(CliBadInput, GeneratedXmlStillReads)
{
  for (const char* compression : { "lz4", "zlib", "none" })
  {
    for (const char* ext : { ".vtp", ".vtu" })
    {
      const std::string cloud = TempPath(std::string("generated-") + compression + ext);
      const CommandResult generate = RunCommand(Pss() + " generate --scene noisy-curve --count 2000 --compression " +
        compression + " -o " + cloud);
      ASSERT_EQ(generate.exitCode, 0) << generate.output;
      const std::string projected = TempPath(std::string("projected-") + compression + ext);
      const CommandResult project = RunCommand(Pss() + " project " + cloud + " --compression " + compression + " -o " +
        projected);
      EXPECT_EQ(project.exitCode, 0) << cloud << ": " << project.output;
      // pss's own output reads back too.
      const CommandResult again = RunCommand(Pss() + " project " + projected + " -o " + TempPath("again.csv"));
      EXPECT_EQ(again.exitCode, 0) << projected << ": " << again.output;
    }
    const std::string cloud = TempPath(std::string("generated-") + compression + ".vtp");
    const std::string field = TempPath(std::string("field-") + compression + ".vti");
    const CommandResult sample = RunCommand(Pss() + " sample " + cloud + " --grid 11,11 --compression " + compression +
      " -o " + field);
    ASSERT_EQ(sample.exitCode, 0) << sample.output;
    const CommandResult probe = RunCommand(Pss() + " sample " + cloud + " --probe " + field + " -o " +
      TempPath("probed.vti"));
    EXPECT_EQ(probe.exitCode, 0) << field << ": " << probe.output;
  }
}

// Missing arrays: the only array pss needs is the points; a table without x and y columns, a VTP
// without points and a start-point file without points are refused or give an empty result.
TEST(CliBadInput, MissingPointArrays)
{
  ExpectRejected(Write("no-xy.csv", "a,b,c\n1,2,3\n"), "the header has no x and y columns");
  const std::string noPoints = Write("no-points.vtp",
    "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<PolyData>\n"
    "<Piece NumberOfPoints=\"0\" NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n"
    "</Piece>\n</PolyData>\n</VTKFile>\n");
  ExpectRejected(noPoints, "empty");
  ExpectRejected(Write("ply-without-vertex.ply", "ply\nformat ascii 1.0\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n"),
    "no 'vertex' element");

  // Start points without points: nothing to project, an empty result and exit 0.
  std::string line = "x,y\n";
  for (int i = 0; i < 40; ++i)
  {
    line += std::to_string(0.1 * i) + ",0\n";
  }
  const std::string cloud = Write("line40.csv", line);
  const CommandResult r = RunCommand(Pss() + " project " + cloud + " --h 0.5 --start " + noPoints + " -o " +
    TempPath("no-starts.csv"));
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

// Grids of 0 or 10^10 samples are refused at once (exit 1), a malformed --grid is a usage error (2).
TEST(CliBadInput, AbsurdGrids)
{
  std::string line = "x,y\n";
  for (int i = 0; i < 40; ++i)
  {
    line += std::to_string(0.1 * i) + ",0\n";
  }
  const std::string cloud = Write("line40-grid.csv", line);
  for (const char* grid : { "100000,100000", "0,0", "10,-3" })
  {
    const CommandResult r = RunCommand(Pss() + " sample " + cloud + " --h 0.5 --grid " + grid + " -o " +
      TempPath("grid.vti"));
    EXPECT_EQ(r.exitCode, 1) << grid << ": " << r.output;
    EXPECT_NE(r.output.find("SampleDimensions"), std::string::npos) << grid << ": " << r.output;
  }
  const CommandResult usage = RunCommand(Pss() + " sample " + cloud + " --grid 10 -o " + TempPath("grid.vti"));
  EXPECT_EQ(usage.exitCode, 2) << usage.output;
}

// PCD: the reader's checks reach the tool as exit 1 and their message (the full list is
// PCDBadInput.* of the pipeline stage); an empty cloud is refused by the surface.
TEST(CliBadInput, MalformedPcd)
{
  const std::string fields = "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n";
  ExpectRejected(Write("empty.pcd", ""), "the file is empty");
  ExpectRejected(Write("header-only.pcd", fields + "WIDTH 3\nHEIGHT 1\nPOINTS 3\n"), "without a DATA line");
  ExpectRejected(Write("negative.pcd", fields + "WIDTH -3\nHEIGHT 1\nPOINTS 3\nDATA ascii\n"),
    "WIDTH '-3' is not a non-negative integer");
  ExpectRejected(Write("claims.pcd", fields + "WIDTH 100000000\nHEIGHT 1\nPOINTS 100000000\nDATA binary\n1234"),
    "truncated: POINTS 100000000 x 12 bytes");
  ExpectRejected(Write("bomb.pcd", fields + "WIDTH 100000000\nHEIGHT 1\nPOINTS 100000000\nDATA binary_compressed\n" +
                                     std::string("\x08\0\0\0\0\x8c\x86\x47", 8) + std::string(8, '\x1f')),
    "more than LZF's largest ratio");
  ExpectRejected(Write("kind.pcd", fields + "WIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA text\n1 2 3\n"), "unknown DATA kind 'text'");
  ExpectRejected(Write("sizes.pcd", "FIELDS x y z\nSIZE 4 4\nTYPE F F F\nWIDTH 1\nPOINTS 1\nDATA ascii\n1 2 3\n"),
    "has 2 SIZE, 3 TYPE");
  ExpectRejected(Write("zero.pcd", fields + "WIDTH 0\nHEIGHT 1\nPOINTS 0\nDATA binary\n"), "empty");
}

// --viewpoint: not three numbers is a usage error (exit 2); a non-finite one the filter's error.
TEST(CliBadInput, ViewpointFlag)
{
  std::string grid;
  for (int i = 0; i < 100; ++i)
  {
    grid += std::to_string(0.1 * (i % 10)) + " " + std::to_string(0.1 * (i / 10)) + " 0\n";
  }
  const std::string cloud = Write("viewpoint-grid.xyz", grid);
  const std::string out = " -o " + TempPath("viewpoint-out.vtp");
  CommandResult r = RunCommand(Pss() + " project " + cloud + " --viewpoint 1,2" + out);
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("--viewpoint takes X,Y,Z, input or off, not '1,2'"), std::string::npos) << r.output;
  r = RunCommand(Pss() + " project " + cloud + " --viewpoint 0,nan,1" + out);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("is not finite"), std::string::npos) << r.output;
  r = RunCommand(Pss() + " project " + cloud + " --viewpoint 0,0,1 --h 0.3" + out);
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

// The per-point scale flags: bad values are usage errors (exit 2); a missing or bad Scale array and
// a viewpoint at a cloud point are the filter's errors (exit 1).
TEST(CliBadInput, PointScaleFlags)
{
  std::string grid;
  for (int i = 0; i < 100; ++i)
  {
    grid += std::to_string(0.1 * (i % 10)) + " " + std::to_string(0.1 * (i / 10)) + " 0\n";
  }
  const std::string cloud = Write("scales-grid.xyz", grid);
  const std::string out = " -o " + TempPath("scales-out.vtp");
  const std::pair<const char*, const char*> usage[] = {
    { " --scale-multiplier 0", "--scale-multiplier" },
    { " --scale-multiplier -2", "--scale-multiplier" },
    { " --point-scale-multiplier 0", "--point-scale-multiplier expects a number in [0.01, 100]" },
    { " --scale-spread 0.5", "--scale-spread expects a ratio >= 1" },
    { " --point-scales sometimes", "point-scales" },
  };
  for (const auto& [flags, message] : usage)
  {
    const CommandResult r = RunCommand(Pss() + " project " + cloud + flags + out);
    EXPECT_EQ(r.exitCode, 2) << flags << ": " << r.output;
    EXPECT_NE(r.output.find(message), std::string::npos) << flags << ": " << r.output;
  }
  CommandResult r = RunCommand(Pss() + " project " + cloud + " --point-scales array" + out);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("no one-component point array named \"Scale\""), std::string::npos) << r.output;
  r = RunCommand(Pss() + " project " + cloud + " --viewpoint 0.3,0.4,0" + out);
  EXPECT_EQ(r.exitCode, 1) << r.output;
  EXPECT_NE(r.output.find("is cloud point 43"), std::string::npos) << r.output;
  r = RunCommand(Pss() + " project " + cloud + " --point-scales estimated" + out + " --verbose");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("(median of a scale per point)"), std::string::npos) << r.output;
}
