// Every message type refuses forged and truncated bytes before lcm-gen's
// decode sees them: truncated at every byte, each length field at -1, 0,
// 2^31-1, INT32_MIN and bytes-left+1. Refused messages are counted and
// allocate nothing (a counting operator new watches each decode).
#include "mrsim/wire_check.hpp"

#include <gtest/gtest.h>

#include <climits>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

#include "all_message_types.h"
#include "lcmtypes/runtime/decode.h"
#include "logger/lcm_type_registry.h"
#include "wire_sample.h"

namespace {

// Bytes allocated by this thread while `counting` is set.
thread_local bool counting = false;
thread_local size_t allocated = 0;

}  // namespace

// gcc pairs the inlined malloc with operator new's own semantics and warns
// that free does not match: it does, this operator new is malloc.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void* operator new(size_t size) {
  if (counting) allocated += size;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
void operator delete(void* p) noexcept { std::free(p); }
void operator delete(void* p, size_t) noexcept { std::free(p); }

namespace mrsim {
namespace {

using testing::BuildWireSample;
using testing::PutBigEndian;
using testing::WireSample;

template <class T>
class WireCheck : public ::testing::Test {
 protected:
  void SetUp() override {
    const LcmStruct* type = registry_.FindByHash(T::getHash());
    ASSERT_NE(type, nullptr);
    name_ = type->name;
    sample_ = BuildWireSample(registry_, *type, T::getHash());
  }

  // Decodes `bytes` with DecodeMessage, expecting it refused, counted, and
  // nothing allocated; `what` says which forgery this is.
  void ExpectRefused(const std::vector<uint8_t>& bytes, size_t size,
                     const std::string& what) {
    T msg;
    WireError error;
    const int64_t before = WireRejections().load();
    allocated = 0;
    counting = true;
    const bool ok = DecodeMessage(bytes.data(), size, &msg, &error);
    counting = false;
    EXPECT_FALSE(ok) << name_ << ": " << what;
    EXPECT_EQ(WireRejections().load(), before + 1) << name_ << ": " << what;
    EXPECT_EQ(allocated, 0u) << name_ << ": " << what;
    EXPECT_NE(std::string(error.field), "") << name_ << ": " << what;
  }

  LcmTypeRegistry registry_ = LcmTypeRegistry::WithBuiltinTypes();
  std::string name_;
  WireSample sample_;
};

TYPED_TEST_SUITE(WireCheck, testing::AllMessageTypes);

TYPED_TEST(WireCheck, WholeMessageDecodesAndEncodesToTheSameBytes) {
  const std::vector<uint8_t>& bytes = this->sample_.bytes;
  TypeParam msg;
  WireError error;
  ASSERT_TRUE(DecodeMessage(bytes.data(), bytes.size(), &msg, &error))
      << this->name_ << ": " << error.field << ": " << error.problem;
  std::vector<uint8_t> again(static_cast<size_t>(msg.getEncodedSize()));
  ASSERT_EQ(msg.encode(again.data(), 0, static_cast<int>(again.size())),
            static_cast<int>(again.size()));
  EXPECT_EQ(again, bytes) << this->name_;
}

TYPED_TEST(WireCheck, MessageTruncatedAtEveryByteIsRefused) {
  const std::vector<uint8_t>& bytes = this->sample_.bytes;
  for (size_t size = 0; size < bytes.size(); ++size) {
    this->ExpectRefused(bytes, size, "truncated to " + std::to_string(size));
  }
}

TYPED_TEST(WireCheck, BytesAfterTheMessageAreRefused) {
  std::vector<uint8_t> bytes = this->sample_.bytes;
  bytes.push_back(0);
  this->ExpectRefused(bytes, bytes.size(), "one byte more");
}

TYPED_TEST(WireCheck, AnotherTypesFingerprintIsRefused) {
  std::vector<uint8_t> bytes = this->sample_.bytes;
  bytes[7] ^= 1;
  this->ExpectRefused(bytes, bytes.size(), "fingerprint changed");
}

TYPED_TEST(WireCheck, EveryForgedLengthIsRefused) {
  for (const testing::LengthField& f : this->sample_.lengths) {
    const size_t left = this->sample_.bytes.size() - f.offset - f.bytes;
    const int64_t widest = f.bytes == 1 ? INT8_MAX : INT32_MAX;
    const int64_t narrowest = f.bytes == 1 ? INT8_MIN : INT32_MIN;
    for (int64_t value : {int64_t{-1}, int64_t{0}, widest, narrowest,
                          std::min<int64_t>(widest, int64_t(left) + 1)}) {
      std::vector<uint8_t> bytes = this->sample_.bytes;
      PutBigEndian(&bytes, f.offset, f.bytes, value);
      this->ExpectRefused(bytes, bytes.size(),
                          f.name + " = " + std::to_string(value));
    }
  }
}

TYPED_TEST(WireCheck, EveryStringAndArrayHasALengthToForge) {
  // Guards the test itself: the samples exercise every length.
  const std::vector<uint8_t>& bytes = this->sample_.bytes;
  size_t lengths = 0;
  for (const testing::LengthField& f : this->sample_.lengths) {
    EXPECT_LE(f.offset + f.bytes, bytes.size());
    ++lengths;
  }
  const LcmStruct* type = this->registry_.FindByHash(TypeParam::getHash());
  bool has_variable = false;
  for (const LcmMember& m : type->members) {
    has_variable = has_variable || m.type == "string";
    for (const LcmDimension& d : m.dims)
      has_variable = has_variable || d.variable;
  }
  if (has_variable) {
    EXPECT_GT(lengths, 0u) << this->name_;
  }
}

TEST(WireCheck, NamesTheFieldAndWhatWasWrong) {
  robot_state_t m{};
  m.robot = "snake";
  std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  // utime, seq, then robot's length: make it 2^31-1.
  PutBigEndian(&bytes, 8 + 16, 4, INT32_MAX);
  WireError error;
  EXPECT_FALSE(CheckWire<robot_state_t>(bytes.data(), bytes.size(), &error));
  EXPECT_STREQ(error.field, "robot_state_t.robot");
  EXPECT_STREQ(error.problem, "string over its maximum");
}

TEST(WireCheck, ArrayOverItsDeclaredMaximumIsRefusedEvenWhenTheBytesAreThere) {
  joint_command_t m{};
  m.num_joints = 4097;  // max: 4096 in joint_command_t.lcm
  m.target.assign(4097, 0.0);
  std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  WireError error;
  EXPECT_FALSE(CheckWire<joint_command_t>(bytes.data(), bytes.size(), &error));
  EXPECT_STREQ(error.problem, "array length over its maximum");
  m.num_joints = 4096;
  m.target.resize(4096);
  bytes.resize(static_cast<size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  EXPECT_TRUE(CheckWire<joint_command_t>(bytes.data(), bytes.size(), &error));
}

// Processes decode into a reused message: one whose array is empty must
// not keep the previous message's elements (lcm-gen's decode leaves them),
// nor a nested one (a sensor module's readings).
TEST(DecodeMessage, AnEmptyArrayAfterAFullOneDecodesEmpty) {
  auto encode = [](const auto& msg) {
    std::vector<uint8_t> b(static_cast<size_t>(msg.getEncodedSize()));
    msg.encode(b.data(), 0, static_cast<int>(b.size()));
    return b;
  };
  mrsim::joint_command_t full{};
  full.robot = "snake";
  full.sender = "gait";
  full.num_joints = 3;
  full.target = {0.1, 0.2, 0.3};
  mrsim::joint_command_t empty = full;
  empty.sender = "mrsim-camera";
  empty.num_joints = 0;
  empty.target.clear();
  mrsim::joint_command_t reused{};
  const auto a = encode(full);
  ASSERT_TRUE(mrsim::DecodeMessage(a.data(), a.size(), &reused));
  EXPECT_EQ(reused.target.size(), 3u);
  const auto b = encode(empty);
  ASSERT_TRUE(mrsim::DecodeMessage(b.data(), b.size(), &reused));
  EXPECT_TRUE(reused.target.empty());

  mrsim::robot_state_t state{};
  state.robot = "snake";
  state.num_sensor_modules = 1;
  state.sensor_modules.resize(1, mrsim::sensor_module_state_t{});
  mrsim::sensor_reading_t reading{};
  reading.kind = "imu";
  reading.num_values = 2;
  reading.values = {1.0, 2.0};
  state.sensor_modules[0].num_readings = 1;
  state.sensor_modules[0].readings = {reading};
  mrsim::robot_state_t bare = state;
  bare.sensor_modules[0].num_readings = 0;
  bare.sensor_modules[0].readings.clear();
  mrsim::robot_state_t reused_state{};
  const auto c = encode(state);
  ASSERT_TRUE(mrsim::DecodeMessage(c.data(), c.size(), &reused_state));
  EXPECT_EQ(reused_state.sensor_modules.at(0).readings.size(), 1u);
  const auto d = encode(bare);
  ASSERT_TRUE(mrsim::DecodeMessage(d.data(), d.size(), &reused_state));
  EXPECT_TRUE(reused_state.sensor_modules.at(0).readings.empty());
}

}  // namespace

TEST(WireCheck,
     AReaderWithoutTheKeyDecodesSignedMessagesAndNothingElseAfterThem) {
  robot_state_t m{};
  m.robot = "snake";
  m.seq = 42;
  std::vector<uint8_t> bytes(static_cast<size_t>(m.getEncodedSize()));
  m.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  MessageAuth auth(std::string(32, 'k'));
  std::vector<uint8_t> signed_bytes;
  auth.Sign("MRSIM_STATE_snake", bytes.data(), bytes.size(), 1000,
            &signed_bytes);
  ASSERT_EQ(signed_bytes.size(), bytes.size() + MessageAuth::kTrailerSize);
  robot_state_t got{};
  EXPECT_TRUE(DecodeMessage(signed_bytes.data(), signed_bytes.size(), &got));
  EXPECT_EQ(got.seq, 42);
  EXPECT_EQ(got.robot, "snake");
  // Any other bytes after a message are still refused.
  std::vector<uint8_t> padded = bytes;
  padded.resize(bytes.size() + MessageAuth::kTrailerSize, 0);
  EXPECT_FALSE(DecodeMessage(padded.data(), padded.size(), &got));
}
}  // namespace mrsim
