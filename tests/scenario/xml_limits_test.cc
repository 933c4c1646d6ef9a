// Scenario files at the edges: each class of hostile file is refused with
// file, line and field, before it can exhaust memory or the stack.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>
#include <vector>

#include "common/input_limits.h"
#include "sim_core/mesh/base64.h"
#include "sim_core/scenario/chain_builder.h"
#include "sim_core/scenario/scenario_schema.h"
#include "sim_core/scenario/scenario_xml.h"
#include "tests/common/child_process.h"

namespace mrsim {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;
using testing::TempDir;

std::string ErrorReading(const std::string& path) {
  try {
    ReadScenarioFile(path);
  } catch (const ScenarioError& e) {
    return e.what();
  }
  return "";
}

std::string Write(const std::string& dir, const std::string& name,
                  const std::string& text) {
  const std::string path = dir + "/" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(ScenarioLimits, AFileOverTheSizeCapIsRefusedNamingIt) {
  const std::string dir = TempDir("scenario_limits_size");
  // Stands for a file with a 1 GB attribute: sparse, refused unread.
  const std::string path = Write(dir, "huge.xml", "<Scenario frame=\"z-up\">");
  std::filesystem::resize_file(path, kMaxInputFileBytes + 1);
  EXPECT_EQ(ErrorReading(path),
            path + ": larger than 64 MiB, the most mrsim reads from one file");
}

TEST(ScenarioLimits, XmlNestedTenThousandDeepIsRefusedAtItsLine) {
  const std::string dir = TempDir("scenario_limits_depth");
  std::string xml = "<Scenario frame=\"z-up\">\n<robot>\n";
  for (int i = 0; i < 10000; ++i) xml += "<name>";
  const std::string path = Write(dir, "deep.xml", xml);
  EXPECT_EQ(ErrorReading(path),
            path +
                ":3: elements nested more than 32 deep, more than any "
                "mrsim file has");
}

TEST(ScenarioLimits, ALongAttributeIsRefusedAtItsLine) {
  const std::string dir = TempDir("scenario_limits_attribute");
  const std::string path =
      Write(dir, "attr.xml",
            "<Scenario frame=\"z-up\"\n note=\"" +
                std::string(kMaxXmlAttributeBytes + 1, 'x') + "\"/>\n");
  EXPECT_THAT(ErrorReading(path),
              StartsWith(path + ":2: an attribute value longer than 64 KiB"));
}

TEST(ScenarioLimits, MoreModulesThanTheCapAreRefusedBeforeAnyIsRead) {
  const std::string dir = TempDir("scenario_limits_modules");
  std::string xml = "<Scenario frame=\"z-up\">\n<robot>\n<modules>\n";
  for (int i = 0; i < kMaxModules + 1; ++i) xml += "<Module />\n";
  const std::string path =
      Write(dir, "many.xml", xml + "</modules>\n</robot>\n</Scenario>\n");
  EXPECT_EQ(ErrorReading(path),
            path +
                ":1004: Scenario/robot[1]/modules/Module[1001]: more than "
                "1000 <Module> in <modules> (at most 1000: " +
                kMaxModulesWhy + ")");
  EXPECT_THROW(
      {
        ChainOptions options;
        options.modules = 1000000000;
        MakeChain(options);
      },
      std::invalid_argument);
}

TEST(ScenarioLimits, NanAndOverflowingNumbersAreRefusedNamingTheField) {
  const std::string dir = TempDir("scenario_limits_numbers");
  Scenario s;
  ChainOptions options;
  options.modules = 1;
  s.robots.push_back(MakeChain(options));
  const std::string good = WriteScenarioString(s);
  const std::string kMass =
      "<mass>" + FormatNumber(s.robots[0].modules[0].frames[0].mass) +
      "</mass>";
  ASSERT_NE(good.find(kMass), std::string::npos);
  for (const char* bad : {"NaN", "nan", "inf", "1e309", "-1e400"}) {
    std::string xml = good;
    xml.replace(xml.find(kMass), kMass.size(),
                std::string("<mass>") + bad + "</mass>");
    const std::string path = Write(dir, "n.xml", xml);
    EXPECT_THAT(ErrorReading(path),
                HasSubstr("/frames/Frame[1]/mass: expected a number, got '" +
                          std::string(bad) + "'"));
  }
  std::string xml = good;
  xml.replace(xml.find(kMass), kMass.size(), "<mass>1e308</mass>");
  EXPECT_THAT(ErrorReading(Write(dir, "n.xml", xml)),
              HasSubstr("/frames/Frame[1]/mass: expected a value within"));
}

// 8-byte signature and an IHDR chunk: all stb_image reads of the header.
std::vector<unsigned char> PngHeader(unsigned width, unsigned height) {
  std::vector<unsigned char> b = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n',
                                  0,    0,   0,   13,  'I',  'H',  'D',  'R'};
  for (unsigned v : {width, height}) {
    for (int shift = 24; shift >= 0; shift -= 8) b.push_back(v >> shift);
  }
  for (unsigned char c : {8, 0, 0, 0, 0, 0, 0, 0, 0}) b.push_back(c);
  return b;
}

TEST(ScenarioLimits, AnImageHeaderClaimingTenGigapixelsIsRefusedUndecoded) {
  const std::string dir = TempDir("scenario_limits_image");
  Scenario s;
  ChainOptions options;
  options.modules = 1;
  s.robots.push_back(MakeChain(options));
  s.scene.height_image = "base64:" + Base64Encode(PngHeader(100000, 100000));
  const std::string path = dir + "/image.xml";
  WriteScenarioFile(s, path);
  const std::string error = ErrorReading(path);
  EXPECT_THAT(error, HasSubstr("Scenario/scene/height_Image: cannot read the "
                               "height image"));
  EXPECT_THAT(error, HasSubstr("its header claims more pixels than can be "
                               "decoded; at most 16384 on a side and "
                               "16777216 in all"));
  // Headers stb would decode: 20000 on a side, 25 million pixels.
  for (const auto& [w, h, what] :
       {std::make_tuple(20000u, 2u, "20000x2 pixels"),
        std::make_tuple(5000u, 5000u, "5000x5000 pixels")}) {
    s.scene.height_image = "base64:" + Base64Encode(PngHeader(w, h));
    WriteScenarioFile(s, path);
    EXPECT_THAT(ErrorReading(path), HasSubstr(what));
  }
  // The same bytes as a file beside the scenario.
  std::ofstream(dir + "/big.png", std::ios::binary)
      .write(reinterpret_cast<const char*>(PngHeader(8000, 8000).data()), 33);
  s.scene.height_image = "big.png";
  WriteScenarioFile(s, path);
  EXPECT_THAT(ErrorReading(path), HasSubstr("8000x8000 pixels"));
}

// A chunk: length, type, body and a CRC stb does not check.
void AppendChunk(std::vector<unsigned char>* png, const std::string& type,
                 const std::vector<unsigned char>& body, uint32_t length) {
  for (int shift = 24; shift >= 0; shift -= 8) png->push_back(length >> shift);
  png->insert(png->end(), type.begin(), type.end());
  png->insert(png->end(), body.begin(), body.end());
  for (int k = 0; k < 4; ++k) png->push_back(0);
}

std::string ImageError(const std::vector<unsigned char>& png) {
  const std::string dir = TempDir("scenario_limits_png");
  Scenario s;
  ChainOptions options;
  options.modules = 1;
  s.robots.push_back(MakeChain(options));
  s.scene.height_image = "base64:" + Base64Encode(png);
  const std::string path = dir + "/image.xml";
  WriteScenarioFile(s, path);
  return ErrorReading(path);
}

TEST(ScenarioLimits, APngChunkClaimingMoreBytesThanAreLeftIsRefused) {
  // 70 bytes once made the image decoder allocate 2 GiB for a chunk that
  // claimed 1.5 GB (fuzz/regressions/height_image/).
  std::vector<unsigned char> png = PngHeader(4, 3);
  AppendChunk(&png, "IDAT", {0x78, 0x9c, 0x63, 0x60}, 0x59000023u);
  EXPECT_THAT(ImageError(png),
              HasSubstr("not a valid PNG: chunk 'IDAT' at byte 33 claims "
                        "1493172259 bytes; only 4 are left"));
  // The same chunk cut inside its header: stb would read the missing bytes
  // as zeros and still find a length of gigabytes.
  png.resize(33 + 7);
  EXPECT_THAT(ImageError(png),
              HasSubstr("not a valid PNG: it ends inside the chunk at byte 33 "
                        "(7 of at least 12 bytes)"));
}

TEST(ScenarioLimits, APngWhoseDataInflatesBeyondItsPixelsIsRefused) {
  // A 2x2 image whose data inflates to 10 MB: a zip bomb for the decoder.
  const std::vector<unsigned char> zeros(10'000'000, 0);
  uLongf packed_size = compressBound(zeros.size());
  std::vector<unsigned char> packed(packed_size);
  ASSERT_EQ(compress(packed.data(), &packed_size, zeros.data(), zeros.size()),
            Z_OK);
  packed.resize(packed_size);
  std::vector<unsigned char> png = PngHeader(2, 2);
  AppendChunk(&png, "IDAT", packed, static_cast<uint32_t>(packed.size()));
  AppendChunk(&png, "IEND", {}, 0);
  EXPECT_THAT(ImageError(png),
              HasSubstr("not a valid PNG: its image data inflates to more "
                        "than the 1058 bytes its header's pixels need"));
  // The same image with the data it needs decodes.
  const std::vector<unsigned char> pixels(2 * 3, 0);
  packed_size = compressBound(pixels.size());
  packed.assign(packed_size, 0);
  ASSERT_EQ(compress(packed.data(), &packed_size, pixels.data(), pixels.size()),
            Z_OK);
  packed.resize(packed_size);
  png = PngHeader(2, 2);
  AppendChunk(&png, "IDAT", packed, static_cast<uint32_t>(packed.size()));
  AppendChunk(&png, "IEND", {}, 0);
  EXPECT_EQ(ImageError(png), "");
}

}  // namespace
}  // namespace mrsim
