// SPDX-License-Identifier: BSD-3-Clause
// The pss tool on unreadable, malformed and absurd input, as the README's bad-input table states
// it: every case exits 1 with a message that says what is wrong (never a crash, which RunCommand
// reports as exit -1), and nothing is written.
#include "CliTestUtilities.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
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
// face index past the vertices: a segfault found by Fuzz.cli_input).
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
    "empty");
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
