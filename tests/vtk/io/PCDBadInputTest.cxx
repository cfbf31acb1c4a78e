// SPDX-License-Identifier: BSD-3-Clause
/**
 * vtkPCDReader on files that lie or are broken: each fails the update with an error naming what is
 * wrong, before anything the size of the claim is allocated (a claim of gigabytes in a file of a
 * few hundred bytes would otherwise exhaust memory or take seconds). Rows of docs/bad-input.md.
 */
#include "PCDTestUtilities.h"

#include "vtkPointData.h"

#include <gtest/gtest.h>

using namespace pcd_test;

namespace
{

const std::string kXyzFields = "VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 1\n";

std::string Dimensions(const std::string& width, const std::string& height, const std::string& points)
{
  return "WIDTH " + width + "\nHEIGHT " + height + "\nVIEWPOINT 0 0 0 1 0 0 0\nPOINTS " + points + "\n";
}

// Twelve bytes per point: @p n points of (i, 2i, 3i).
std::string FloatPoints(int n)
{
  std::string body;
  for (int i = 0; i < n; ++i)
  {
    body += Bytes(float(i)) + Bytes(float(2 * i)) + Bytes(float(3 * i));
  }
  return body;
}

void ExpectError(const std::string& name, const std::string& bytes, const std::string& message)
{
  SCOPED_TRACE(name);
  const Read r = ReadBytes(name + ".pcd", bytes);
  EXPECT_FALSE(r.ok) << "expected the error '" << message << "'";
  EXPECT_TRUE(r.errors->HasError(message)) << (r.errors->Errors.empty() ? "(no error)" : r.errors->Errors.front());
  EXPECT_EQ(r.output->GetNumberOfPoints(), 0);
}

} // namespace

TEST(PCDBadInput, EmptyAndHeaderOnlyFiles)
{
  ExpectError("empty", "", "the file is empty");
  ExpectError("header-only", kXyzFields + Dimensions("3", "1", "3"), "without a DATA line");
  ExpectError("not-pcd", "ply\nformat ascii 1.0\nend_header\n", "unknown keyword 'ply'");
  const Read missing = ReadPCD(TestPath("no-such-file.pcd"));
  EXPECT_TRUE(missing.errors->HasError("cannot open"));
}

TEST(PCDBadInput, PointsZeroIsAnEmptyCloud)
{
  // A valid file without points: an empty output and no error here; the filters and `pss` then
  // refuse the empty cloud with their own message.
  const Read r = ReadBytes("points-zero", kXyzFields + Dimensions("0", "1", "0") + "DATA binary\n");
  EXPECT_TRUE(r.ok);
  EXPECT_EQ(r.output->GetNumberOfPoints(), 0);
  const Read c = ReadBytes("points-zero-compressed", kXyzFields + Dimensions("0", "1", "0") + "DATA binary_compressed\n");
  EXPECT_TRUE(c.ok);
}

TEST(PCDBadInput, DimensionsThatAreNegativeAbsurdOrInconsistent)
{
  ExpectError("negative-width", kXyzFields + Dimensions("-640", "480", "307200") + "DATA binary\n",
    "WIDTH '-640' is not a non-negative integer");
  ExpectError("width-beyond-2^64", kXyzFields + Dimensions("99999999999999999999999", "1", "3") + "DATA binary\n",
    "below 2^64");
  ExpectError("width-times-height", kXyzFields + Dimensions("640", "480", "3") + "DATA binary\n",
    "POINTS 3 is not WIDTH x HEIGHT (640 x 480)");
  ExpectError("overflowing-grid", kXyzFields + Dimensions("4294967296", "4294967296", "0") + "DATA binary\n",
    "overflows");
  // An absurd WIDTH that agrees with POINTS: refused because the file cannot hold it.
  ExpectError("absurd-width", kXyzFields + Dimensions("1000000000000", "1", "1000000000000") + "DATA binary\n" +
      FloatPoints(4),
    "truncated: POINTS 1000000000000 x 12 bytes");
  ExpectError("absurd-ascii", kXyzFields + Dimensions("1000000000000", "1", "1000000000000") + "DATA ascii\n1 2 3\n",
    "ASCII values cannot fit");
  ExpectError("bad-viewpoint", kXyzFields + "WIDTH 1\nHEIGHT 1\nVIEWPOINT 0 0 0 1 0 0\nPOINTS 1\nDATA ascii\n1 2 3\n",
    "VIEWPOINT takes 7 numbers");
}

TEST(PCDBadInput, FieldsWhoseSizesDoNotAddUp)
{
  const std::string tail = Dimensions("1", "1", "1") + "DATA ascii\n1 2 3\n";
  ExpectError("size-count", "FIELDS x y z\nSIZE 4 4\nTYPE F F F\n" + tail, "has 2 SIZE, 3 TYPE");
  ExpectError("count-count", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1\n" + tail, "and 2 COUNT entries");
  ExpectError("size-3", "FIELDS x y z\nSIZE 4 4 3\nTYPE F F F\n" + tail, "SIZE 3 is not 1, 2, 4 or 8");
  ExpectError("float-2", "FIELDS x y z\nSIZE 4 4 2\nTYPE F F F\n" + tail, "TYPE F needs SIZE 4 or 8");
  ExpectError("type-x", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F X\n" + tail, "TYPE X is not I, U or F");
  ExpectError("count-0", "FIELDS x y z\nSIZE 4 4 4\nTYPE F F F\nCOUNT 1 1 0\n" + tail, "COUNT 0 is outside");
  ExpectError("no-fields", "VERSION 0.7\n" + tail, "no FIELDS line");
  ExpectError("twice", "FIELDS x y x\nSIZE 4 4 4\nTYPE F F F\n" + tail, "the field 'x' appears twice");
  ExpectError("no-z", "FIELDS x y w\nSIZE 4 4 4\nTYPE F F F\n" + tail, "no single-element field 'z'");
  ExpectError("keyword-twice", kXyzFields + "WIDTH 1\nWIDTH 1\nHEIGHT 1\nPOINTS 1\nDATA ascii\n1 2 3\n",
    "WIDTH appears twice");
}

TEST(PCDBadInput, UnknownDataKindAndTruncatedBodies)
{
  const std::string head = kXyzFields + Dimensions("4", "1", "4");
  ExpectError("data-kind", head + "DATA binary_lz4\n" + FloatPoints(4), "unknown DATA kind 'binary_lz4'");
  ExpectError("truncated-binary", head + "DATA binary\n" + FloatPoints(4).substr(0, 40), "truncated");
  ExpectError("truncated-ascii", head + "DATA ascii\n1.000000 2.000000 3.000000\n4.000000 5.000000 6.000000\n",
    "the body has 2 points, POINTS says 4");
  ExpectError("ascii-far-too-short", head + "DATA ascii\n1 2 3\n", "ASCII values cannot fit");
  ExpectError("ascii-columns", head + "DATA ascii\n1 2 3\n4 5\n7 8 9\n1 1 1\n", "expected 3 values, found 2");
  ExpectError("ascii-word", head + "DATA ascii\n1 2 3\n4 five 6\n7 8 9\n1 1 1\n", "'five' is not a value of field 'y'");
  ExpectError("ascii-range", "FIELDS x y z n\nSIZE 4 4 4 1\nTYPE F F F U\n" + Dimensions("1", "1", "1") +
      "DATA ascii\n1 2 3 256\n",
    "'256' is not a value of field 'n'");
}

TEST(PCDBadInput, CompressedBlocksThatLie)
{
  const std::string head = kXyzFields + Dimensions("4", "1", "4") + "DATA binary_compressed\n";
  const std::string good = CompressedBody(FloatPoints(4));
  ASSERT_TRUE(ReadBytes("compressed-good", head + good).ok);
  ExpectError("no-sizes", head + "\x10\x00", "needs 8 bytes of sizes");
  // The uncompressed size disagrees with POINTS x 12.
  ExpectError("uncompressed-lie",
    head + Bytes(std::uint32_t(good.size() - 8)) + Bytes(std::uint32_t(47)) + good.substr(8),
    "says it holds 47 bytes, but POINTS 4 x 12 bytes per point is 48");
  // The compressed size claims more than the file holds.
  ExpectError("compressed-lie", head + Bytes(std::uint32_t(100000)) + Bytes(std::uint32_t(48)) + good.substr(8),
    "truncated: the compressed block's size is 100000 bytes");
  // A decompression bomb: 10^8 points (1.2 GB) claimed from 40 bytes.
  const std::string bomb = kXyzFields + Dimensions("100000000", "1", "100000000") + "DATA binary_compressed\n" +
    Bytes(std::uint32_t(40)) + Bytes(std::uint32_t(1200000000)) + std::string(40, '\x1f');
  ExpectError("bomb", bomb, "more than LZF's largest ratio (88:1)");
  // Sizes that agree, a block that does not decompress to them.
  std::string corrupt = good;
  corrupt[8 + 33] = '\x1f'; // the second literal run claims 32 bytes where 16 follow: the block overruns
  ExpectError("corrupt-block", head + corrupt, "the LZF block is corrupt");
}
