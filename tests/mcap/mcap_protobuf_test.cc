// mrsim-log --mcap's protobuf encoding: every .lcm type's messages, encoded
// by LcmProtobufEncoder and decoded with the schema made from its .lcm,
// read as the same JSON text as the JSON encoding writes; a recorder's
// protobuf file holds what its JSON file of the same messages does; and a
// hostile schema, payload or LCM message is refused saying what is wrong.
#include <google/protobuf/descriptor.pb.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "logger/lcm_type_registry.h"
#include "logger/mcap/lcm_protobuf_encoder.h"
#include "logger/mcap/lcm_protobuf_schema.h"
#include "logger/mcap/mcap_reader.h"
#include "logger/mcap/mcap_recorder.h"
#include "logger/mcap/protobuf_json_decoder.h"
#include "mrsim/message_json.hpp"
#include "mrsim/robot_state_t.hpp"
#include "mrsim/sim_status_t.hpp"
#include "tests/common/child_process.h"
#include "tests/common/wait_until.h"
#include "tests/logger/test_messages.h"

namespace mrsim {
namespace {

template <class T>
std::vector<uint8_t> Encode(const T& m) {
  std::vector<uint8_t> buf(m.getEncodedSize());
  m.encode(buf.data(), 0, static_cast<int>(buf.size()));
  return buf;
}

// Writes random, well-formed LCM messages of any registry type: small
// arrays, short strings (some bytes not UTF-8), numbers of every sign and
// size, NaN and -0.
class RandomLcm {
 public:
  RandomLcm(const LcmTypeRegistry& registry, uint32_t seed)
      : registry_(registry), rng_(seed) {}

  std::vector<uint8_t> Message(const LcmStruct& type) {
    out_.clear();
    Put(static_cast<uint64_t>(registry_.Fingerprint(type)), 8);
    Struct(type);
    return out_;
  }

 private:
  void Put(uint64_t v, size_t n) {
    for (size_t k = n; k-- > 0;)
      out_.push_back(static_cast<uint8_t>(v >> (8 * k)));
  }
  int Pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(rng_); }

  void Struct(const LcmStruct& s) {
    std::vector<int64_t> ints(s.members.size(), 0);
    for (size_t i = 0; i < s.members.size(); ++i) {
      const LcmMember& m = s.members[i];
      bool is_size = false;
      for (const LcmMember& later : s.members) {
        for (const LcmDimension& d : later.dims) {
          is_size = is_size || (d.variable && d.size == m.name);
        }
      }
      if (m.dims.empty()) {
        ints[i] = Element(m.type, is_size);
        continue;
      }
      int64_t count = 1;
      for (const LcmDimension& d : m.dims) {
        int64_t n = 0;
        if (d.variable) {
          for (size_t j = 0; j < i; ++j) {
            if (s.members[j].name == d.size) n = ints[j];
          }
        } else {
          n = std::stoll(d.size);
        }
        count *= n;
      }
      for (int64_t k = 0; k < count; ++k) Element(m.type, false);
    }
  }

  // Writes one element; returns an integer's value.
  int64_t Element(const std::string& type, bool is_size) {
    if (is_size) {
      const int64_t n = Pick(4);
      Put(static_cast<uint64_t>(n), type == "int8_t"    ? 1
                                    : type == "int16_t" ? 2
                                    : type == "int64_t" ? 8
                                                        : 4);
      return n;
    }
    const int64_t kInts[] = {0, 1, -1, 127, -128, 300, -70000, 1 << 30};
    const int64_t v = kInts[Pick(8)];
    if (type == "int8_t" || type == "byte") {
      Put(static_cast<uint64_t>(v), 1);
    } else if (type == "boolean") {
      Put(Pick(2), 1);
    } else if (type == "int16_t") {
      Put(static_cast<uint64_t>(v), 2);
    } else if (type == "int32_t") {
      Put(static_cast<uint64_t>(v), 4);
    } else if (type == "int64_t") {
      // Unsigned: 2^30 * 2^42 wraps (a huge int64), where signed would be UB.
      Put(static_cast<uint64_t>(v) * 4398046511104ULL, 8);
    } else if (type == "float" || type == "double") {
      const double kReals[] = {0.0, -0.0, 0.1, -2.5e-7, 1e300, std::nan("")};
      double d = kReals[Pick(6)];
      if (type == "float") {
        float f = static_cast<float>(d);
        uint32_t bits = 0;
        std::memcpy(&bits, &f, 4);
        Put(bits, 4);
      } else {
        uint64_t bits = 0;
        std::memcpy(&bits, &d, 8);
        Put(bits, 8);
      }
    } else if (type == "string") {
      const char* const kTexts[] = {"", "snake", "a\"b\\c\n", "caf\xc3\xa9",
                                    "bad\xff\xc3"};
      const std::string t = kTexts[Pick(5)];
      Put(t.size() + 1, 4);
      out_.insert(out_.end(), t.begin(), t.end());
      out_.push_back(0);
    } else {
      Struct(*registry_.FindByName(type));
    }
    return v;
  }

  const LcmTypeRegistry& registry_;
  std::mt19937 rng_;
  std::vector<uint8_t> out_;
};

// JSON text with U+FFFD as JsonWriter escapes it: the protobuf string
// holds the character itself, the same value.
std::string Escaped(std::string text) {
  for (size_t at; (at = text.find("\xEF\xBF\xBD")) != std::string::npos;) {
    text.replace(at, 3, "\\ufffd");
  }
  return text;
}

std::string ProtobufJson(const LcmTypeRegistry& registry, const LcmStruct& type,
                         const std::vector<uint8_t>& lcm) {
  LcmProtobufEncoder encoder(registry, type);
  if (!encoder.Encode(lcm.data(), lcm.size())) return "(not encoded)";
  mcap::ProtobufJsonDecoder decoder(LcmProtobufDescriptorSet(registry, type),
                                    type.full_name(), "test");
  return Escaped(std::string(decoder.ToJson(encoder.view())));
}

TEST(McapProtobuf, EveryLcmTypeReadsBackAsTheJsonEncodingWritesIt) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  ASSERT_TRUE(registry.warnings().empty()) << registry.warnings()[0];
  RandomLcm random(registry, 43);
  int types = 0;
  for (const MessageJsonType& t : MessageJsonTypes()) {
    const LcmStruct* type = registry.FindByHash(t.fingerprint);
    ASSERT_NE(type, nullptr) << t.name;
    ++types;
    for (int round = 0; round < 30; ++round) {
      const std::vector<uint8_t> lcm = random.Message(*type);
      JsonWriter json;
      int64_t seq = 0;
      ASSERT_TRUE(t.to_json(lcm.data(), lcm.size(), json, &seq)) << t.name;
      EXPECT_EQ(ProtobufJson(registry, *type, lcm), std::string(json.view()))
          << t.name << " round " << round;
    }
  }
  EXPECT_GE(types, 15);
}

// What the project's types do not have: multi-dimensional arrays (row
// wrappers), 2-D byte arrays (rows of bytes), every integer size.
const char* const kEveryShape = R"(package test;
struct inner_t { int16_t a; string s[2]; }
struct every_t {
  int8_t i8; int16_t i16; int32_t i32; int64_t i64; byte b; boolean ok;
  float f; double d; string name;
  int32_t rows;
  double grid[rows][3];
  byte planes[2][rows];
  inner_t inner;
  inner_t many[rows];
}
)";

TEST(McapProtobuf, ArraysOfManyDimensionsReadBackAsNestedArrays) {
  LcmTypeRegistry registry;
  registry.AddDefinitions(kEveryShape, "every.lcm");
  const LcmStruct& type = *registry.FindByName("test.every_t");
  std::vector<uint8_t> m;
  auto put = [&](uint64_t v, size_t n) {
    for (size_t k = n; k-- > 0;)
      m.push_back(static_cast<uint8_t>(v >> (8 * k)));
  };
  auto put_double = [&](double d) {
    uint64_t bits = 0;
    std::memcpy(&bits, &d, 8);
    put(bits, 8);
  };
  auto put_string = [&](const std::string& s) {
    put(s.size() + 1, 4);
    m.insert(m.end(), s.begin(), s.end());
    m.push_back(0);
  };
  put(static_cast<uint64_t>(registry.Fingerprint(type)), 8);
  put(static_cast<uint64_t>(-5), 1);
  put(static_cast<uint64_t>(-300), 2);
  put(static_cast<uint64_t>(-70000), 4);
  put(static_cast<uint64_t>(-1), 8);
  put(200, 1);
  put(1, 1);
  float f = 0.5f;
  uint32_t fbits = 0;
  std::memcpy(&fbits, &f, 4);
  put(fbits, 4);
  put_double(-0.0);
  put_string("x");
  put(2, 4);  // rows
  for (double d : {1.0, 2.0, 3.0, 4.0, 5.0, 6.5}) put_double(d);
  for (int b : {1, 2, 3, 255}) put(static_cast<uint64_t>(b), 1);
  put(7, 2);  // inner.a
  put_string("");
  put_string("p");
  for (int k = 0; k < 2; ++k) {
    put(static_cast<uint64_t>(k), 2);
    put_string("q");
    put_string("r");
  }
  EXPECT_EQ(ProtobufJson(registry, type, m),
            "{\"i8\":-5,\"i16\":-300,\"i32\":-70000,\"i64\":-1,\"b\":200,"
            "\"ok\":true,\"f\":0.5,\"d\":-0,\"name\":\"x\",\"rows\":2,"
            "\"grid\":[[1,2,3],[4,5,6.5]],\"planes\":[[1,2],[3,255]],"
            "\"inner\":{\"a\":7,\"s\":[\"\",\"p\"]},"
            "\"many\":[{\"a\":0,\"s\":[\"q\",\"r\"]},"
            "{\"a\":1,\"s\":[\"q\",\"r\"]}]}");

  // The schema is one file of package test, built by libprotobuf.
  google::protobuf::FileDescriptorSet set;
  ASSERT_TRUE(set.ParseFromString(LcmProtobufDescriptorSet(registry, type)));
  ASSERT_EQ(set.file_size(), 1);
  EXPECT_EQ(set.file(0).package(), "test");
  EXPECT_EQ(set.file(0).syntax(), "proto3");
}

TEST(McapProtobuf, ALcmMessageThatIsNotWellFormedEncodesNothing) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  const LcmStruct& type = *registry.FindByName("mrsim.robot_state_t");
  LcmProtobufEncoder encoder(registry, type);
  const auto good = Encode(testing::KnownRobotState(5, 3, 1));
  ASSERT_TRUE(encoder.Encode(good.data(), good.size()));
  EXPECT_TRUE(encoder.has_seq());
  EXPECT_EQ(encoder.seq(), 5);
  for (size_t cut : {size_t{0}, size_t{7}, good.size() / 2, good.size() - 1}) {
    EXPECT_FALSE(encoder.Encode(good.data(), cut)) << cut;
  }
  auto longer = good;
  longer.push_back(0);
  EXPECT_FALSE(encoder.Encode(longer.data(), longer.size()));
  auto other = good;
  other[0] ^= 1;  // not its fingerprint
  EXPECT_FALSE(encoder.Encode(other.data(), other.size()));
  // num_modules (after utime, seq, robot, sim_time) made negative or huge.
  for (uint32_t count : {0xffffffffu, 0x7fffffffu}) {
    robot_state_t state = testing::KnownRobotState(5, 3, 1);
    auto bytes = Encode(state);
    const size_t at = 8 + 8 + 8 + 4 + state.robot.size() + 1 + 8;
    ASSERT_EQ(bytes[at + 3], 3);
    for (int k = 0; k < 4; ++k) {
      bytes[at + k] = static_cast<uint8_t>(count >> (8 * (3 - k)));
    }
    EXPECT_FALSE(encoder.Encode(bytes.data(), bytes.size())) << count;
  }
}

TEST(McapProtobuf, AHostileSchemaOrPayloadIsRefusedSayingWhy) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  const LcmStruct& type = *registry.FindByName("mrsim.sim_status_t");
  const std::string schema = LcmProtobufDescriptorSet(registry, type);
  auto error_of = [](const std::function<void()>& f) -> std::string {
    try {
      f();
    } catch (const mcap::McapError& e) {
      return e.what();
    }
    return "(no error)";
  };
  EXPECT_NE(error_of([] {
              mcap::ProtobufJsonDecoder("\xff\xff", "a.b", "s");
            }).find("s: the protobuf schema is not a FileDescriptorSet"),
            std::string::npos);
  EXPECT_NE(error_of([&] {
              mcap::ProtobufJsonDecoder(schema, "mrsim.nothing_t", "s");
            }).find("has no message mrsim.nothing_t"),
            std::string::npos);
  // A file that imports one the set does not hold.
  google::protobuf::FileDescriptorSet set;
  ASSERT_TRUE(set.ParseFromString(schema));
  set.mutable_file(0)->add_dependency("missing.proto");
  EXPECT_NE(error_of([&] {
              mcap::ProtobufJsonDecoder(set.SerializeAsString(),
                                        "mrsim.sim_status_t", "s");
            }).find("does not build"),
            std::string::npos);

  mcap::ProtobufJsonDecoder decoder(schema, "mrsim.sim_status_t", "chan");
  for (const std::string& bad :
       {std::string("\x0a\xff\xff\xff\xff\x0f", 6),  // length past the end
        std::string("\x08", 1),                      // a tag, no value
        std::string("\x0f\x00", 2)}) {               // wire type 7
    EXPECT_NE(error_of([&] { decoder.ToJson(bad); })
                  .find("chan: a message of " + std::to_string(bad.size()) +
                        " bytes is not a mrsim.sim_status_t"),
              std::string::npos);
  }
  // Deep nesting of a self-containing message: refused by the parse.
  LcmTypeRegistry nested;
  nested.AddDefinitions(
      "package t; struct node_t { int32_t n; node_t kids[n]; }", "n.lcm");
  mcap::ProtobufJsonDecoder tree(
      LcmProtobufDescriptorSet(nested, *nested.FindByName("t.node_t")),
      "t.node_t", "tree");
  std::string chain;  // 300 levels of kids[0]
  for (int k = 0; k < 300; ++k) {
    std::string inner = chain;
    chain = "\x12";
    chain += static_cast<char>(0x80 | (inner.size() & 0x7f));
    chain += static_cast<char>(inner.size() >> 7);
    chain += inner;
  }
  EXPECT_NE(error_of([&] { tree.ToJson(chain); }).find("is not a t.node_t"),
            std::string::npos);
}

TEST(McapProtobuf, ARecordersProtobufFileHoldsWhatItsJsonFileDoes) {
  const std::string dir = testing::TempDir("mcap_protobuf");
  std::vector<std::vector<uint8_t>> messages;
  for (int64_t seq = 0; seq < 40; ++seq) {
    messages.push_back(Encode(testing::KnownRobotState(seq, 5, 2)));
  }
  sim_status_t status{};
  status.clock = "fast\xff";
  status.control_ok = 1;
  status.real_time_factor = std::nan("");
  messages.push_back(Encode(status));
  std::vector<std::string> texts[2];
  std::string encodings[2];
  for (int e = 0; e < 2; ++e) {
    McapRecorderOptions options;
    options.path = dir + (e == 0 ? "/run.pb.mcap" : "/run.json.mcap");
    options.encoding = e == 0 ? McapEncoding::kProtobuf : McapEncoding::kJson;
    McapRecorder recorder(options);
    uint64_t t = 1000;
    for (const auto& m : messages) {
      const bool is_status = &m == &messages.back();
      recorder.OnMessage(is_status ? "MRSIM_SIM_STATUS" : "MRSIM_STATE_snake",
                         m.data(), m.size(), t += 1000);
    }
    recorder.Finish();
    mcap::McapJsonPayloads payloads;
    const mcap::McapSummary summary = mcap::ReadMcap(
        testing::ReadFileText(options.path), options.path,
        [&](const mcap::McapMessage& m) {
          texts[e].push_back(Escaped(std::string(payloads.Text(m))));
          encodings[e] = m.channel->message_encoding + "/" +
                         m.schema->encoding + "/" + m.schema->name;
        });
    EXPECT_TRUE(summary.complete);
  }
  EXPECT_EQ(encodings[0], "protobuf/protobuf/mrsim.sim_status_t");
  EXPECT_EQ(encodings[1], "json/jsonschema/mrsim.sim_status_t");
  ASSERT_EQ(texts[0].size(), 41u);
  EXPECT_EQ(texts[0], texts[1]);
  EXPECT_NE(texts[0][40].find("\"real_time_factor\":null"), std::string::npos)
      << texts[0][40];
}

}  // namespace
}  // namespace mrsim
