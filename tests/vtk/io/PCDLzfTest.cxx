// SPDX-License-Identifier: BSD-3-Clause
// The reader's own LZF decoder against liblzf's, the reference: on valid blocks of every kind of
// content (literal runs, short and long back references, overlapping runs) and on blocks cut,
// corrupted or given too little room, both return the same count and the same bytes.
#include "PointSetSurfacesPCDBody.h"

extern "C"
{
#include <lzf.h>
}

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace
{

using Bytes = std::vector<unsigned char>;

// liblzf's compression of @p raw (empty when it cannot compress into twice the size).
Bytes Compress(const Bytes& raw)
{
  Bytes block(raw.size() * 2 + 64);
  const unsigned int n = lzf_compress(raw.data(), static_cast<unsigned int>(raw.size()), block.data(),
    static_cast<unsigned int>(block.size()));
  block.resize(n);
  return block;
}

// Decodes @p block into @p room bytes with both decoders and expects the same result.
void ExpectSameDecoding(const Bytes& block, std::size_t room, const std::string& what)
{
  Bytes ours(room + 1, 0xAB), theirs(room + 1, 0xAB);
  const std::size_t n =
    pss_pcd::detail::DecodeLzf(block.data(), block.size(), ours.data(), room);
  const unsigned int m = lzf_decompress(block.data(), static_cast<unsigned int>(block.size()), theirs.data(),
    static_cast<unsigned int>(room));
  ASSERT_EQ(n, m) << what;
  EXPECT_EQ(0, std::memcmp(ours.data(), theirs.data(), n)) << what;
  EXPECT_EQ(0xAB, ours[room]) << what << ": wrote past the room it was given";
}

// Contents with each kind of LZF token: random bytes (literals), float columns of a smooth
// surface (a few short matches), a repeating 5-byte pattern (matches 5 behind: the byte-wise path),
// runs of one byte (matches 1 behind), long repeats (the 7 + n length form).
std::vector<std::pair<std::string, Bytes>> Samples()
{
  std::mt19937 random(7);
  std::vector<std::pair<std::string, Bytes>> samples;
  Bytes noise(10000);
  for (auto& b : noise)
  {
    b = static_cast<unsigned char>(random());
  }
  samples.emplace_back("random bytes", noise);
  Bytes floats;
  for (int i = 0; i < 3000; ++i)
  {
    const float v = 0.001f * static_cast<float>(i % 97) + 1.0f;
    const auto* p = reinterpret_cast<const unsigned char*>(&v);
    floats.insert(floats.end(), p, p + 4);
  }
  samples.emplace_back("float column", floats);
  Bytes pattern;
  for (int i = 0; i < 5000; ++i)
  {
    pattern.push_back(static_cast<unsigned char>("abcde"[i % 5]));
  }
  samples.emplace_back("5-byte pattern", pattern);
  samples.emplace_back("one byte repeated", Bytes(7000, 0));
  Bytes mixed;
  for (int block = 0; block < 40; ++block)
  {
    const std::size_t length = random() % 600;
    const bool repeat = random() % 2 == 0 && mixed.size() > 300;
    for (std::size_t k = 0; k < length; ++k)
    {
      mixed.push_back(repeat ? mixed[mixed.size() - 300] : static_cast<unsigned char>(random()));
    }
  }
  samples.emplace_back("mixed runs and repeats", mixed);
  return samples;
}

} // namespace

TEST(PCDLzf, DecodesWhatLiblzfCompressesLikeLiblzf)
{
  for (const auto& [name, raw] : Samples())
  {
    const Bytes block = Compress(raw);
    ASSERT_FALSE(block.empty()) << name;
    Bytes out(raw.size());
    ASSERT_EQ(raw.size(), pss_pcd::detail::DecodeLzf(block.data(), block.size(), out.data(), out.size())) << name;
    EXPECT_EQ(raw, out) << name;
    // Exactly the room, more room, and too little (liblzf refuses what does not fit: so must we).
    ExpectSameDecoding(block, raw.size(), name);
    ExpectSameDecoding(block, raw.size() + 100, name + ", more room");
    ExpectSameDecoding(block, raw.size() - 1, name + ", one byte too little room");
    ExpectSameDecoding(block, raw.size() / 2, name + ", half the room");
  }
}

TEST(PCDLzf, CutAndCorruptBlocksFailLikeLiblzf)
{
  std::mt19937 random(11);
  for (const auto& [name, raw] : Samples())
  {
    const Bytes block = Compress(raw);
    // From one byte on: liblzf reads a first control byte even from an empty block (ours
    // returns 0 there, and the reader never calls it so).
    for (std::size_t cut = 1; cut < block.size(); cut += 1 + block.size() / 200)
    {
      ExpectSameDecoding(Bytes(block.begin(), block.begin() + static_cast<std::ptrdiff_t>(cut)), raw.size(),
        name + ", cut at " + std::to_string(cut));
    }
    for (int trial = 0; trial < 200; ++trial)
    {
      Bytes corrupt = block;
      corrupt[random() % corrupt.size()] = static_cast<unsigned char>(random());
      ExpectSameDecoding(corrupt, raw.size(), name + ", one byte changed");
    }
  }
  EXPECT_EQ(0u, pss_pcd::detail::DecodeLzf(nullptr, 0, nullptr, 0)) << "an empty block";
  // A back reference before the start: the first token reaches 1 byte behind nothing.
  ExpectSameDecoding(Bytes{ 0x20, 0x00 }, 16, "reference before the start");
}
