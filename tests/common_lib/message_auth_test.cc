// MessageAuth: what a receiver with the key takes and refuses, driven by a
// fake clock; and key files (mode, format).
#include "lcmtypes/runtime/message_auth.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "lcmtypes/runtime/message_key.h"
#include "lcmtypes/runtime/usage_error.h"

namespace mrsim {
namespace {

using Verdict = MessageAuth::Verdict;

const std::string kKey = "0123456789abcdef0123456789abcdef";
const std::string kChannel = "MRSIM_SIM_CONTROL";
constexpr std::int64_t kNow = 1'800'000'000'000'000;  // us since epoch

std::vector<std::uint8_t> Payload() { return {1, 2, 3, 4, 5, 6, 7, 8, 9}; }

std::vector<std::uint8_t> Signed(MessageAuth& auth, std::int64_t now = kNow,
                                 const std::string& channel = kChannel) {
  const std::vector<std::uint8_t> p = Payload();
  std::vector<std::uint8_t> out;
  auth.Sign(channel, p.data(), p.size(), now, &out);
  return out;
}

Verdict Check(MessageAuth& auth, const std::vector<std::uint8_t>& m,
              std::int64_t now = kNow, const std::string& channel = kChannel,
              std::size_t* payload = nullptr) {
  std::size_t size = 0;
  const Verdict v = auth.Verify(channel, m.data(), m.size(), now, &size);
  if (payload != nullptr) *payload = size;
  return v;
}

TEST(MessageAuth, SignedMessageVerifiesAndKeepsThePayloadInFront) {
  MessageAuth sender(kKey), receiver(kKey);
  const std::vector<std::uint8_t> m = Signed(sender);
  ASSERT_EQ(m.size(), Payload().size() + MessageAuth::kTrailerSize);
  std::size_t payload = 0;
  EXPECT_EQ(Check(receiver, m, kNow + 1000, kChannel, &payload), Verdict::kOk);
  EXPECT_EQ(payload, Payload().size());
  const std::vector<std::uint8_t> p = Payload();
  EXPECT_TRUE(std::equal(p.begin(), p.end(), m.begin()));
  EXPECT_EQ(receiver.counts().accepted, 1);
}

TEST(MessageAuth, EveryFlippedByteIsForgedOrUnsigned) {
  MessageAuth sender(kKey);
  const std::vector<std::uint8_t> m = Signed(sender);
  for (std::size_t i = 0; i < m.size(); ++i) {
    MessageAuth receiver(kKey);
    std::vector<std::uint8_t> bad = m;
    bad[i] ^= 0x01;
    const Verdict v = Check(receiver, bad);
    // The last two bytes mark a trailer: changed, the message is unsigned.
    EXPECT_EQ(v, i + 2 >= m.size() ? Verdict::kUnsigned : Verdict::kForged)
        << "byte " << i;
  }
}

TEST(MessageAuth, SignatureCoversTheChannel) {
  MessageAuth sender(kKey), receiver(kKey);
  EXPECT_EQ(Check(receiver, Signed(sender), kNow, "MRSIM_COMMAND_snake"),
            Verdict::kForged);
}

TEST(MessageAuth, WrongKeyIsForged) {
  MessageAuth sender("another key, just as long as it"), receiver(kKey);
  EXPECT_EQ(Check(receiver, Signed(sender)), Verdict::kForged);
  EXPECT_EQ(receiver.counts().forged, 1);
}

TEST(MessageAuth, UnsignedAndTruncatedMessagesAreUnsigned) {
  MessageAuth sender(kKey), receiver(kKey);
  EXPECT_EQ(Check(receiver, Payload()), Verdict::kUnsigned);
  EXPECT_EQ(Check(receiver, {}), Verdict::kUnsigned);
  std::vector<std::uint8_t> m = Signed(sender);
  // Cut anywhere: either the marker is gone or the signature is wrong.
  for (std::size_t n = 0; n < m.size(); ++n) {
    const std::vector<std::uint8_t> cut(m.begin(), m.begin() + n);
    EXPECT_NE(Check(receiver, cut), Verdict::kOk) << n << " bytes";
  }
  EXPECT_GE(receiver.counts().unsigned_, 2);
  EXPECT_EQ(receiver.counts().accepted, 0);
}

TEST(MessageAuth, SameMessageTwiceIsAReplay) {
  MessageAuth sender(kKey), receiver(kKey);
  const std::vector<std::uint8_t> m = Signed(sender);
  EXPECT_EQ(Check(receiver, m), Verdict::kOk);
  EXPECT_EQ(Check(receiver, m, kNow + 5), Verdict::kReplayed);
  EXPECT_EQ(receiver.counts().replayed, 1);
}

TEST(MessageAuth, OlderMessageAfterANewerOneIsAReplay) {
  MessageAuth sender(kKey), receiver(kKey);
  const std::vector<std::uint8_t> first = Signed(sender, kNow);
  const std::vector<std::uint8_t> second = Signed(sender, kNow + 10);
  EXPECT_EQ(Check(receiver, second), Verdict::kOk);
  EXPECT_EQ(Check(receiver, first), Verdict::kReplayed);
}

TEST(MessageAuth, StampsIncreaseEvenWhenTheClockDoesNot) {
  MessageAuth sender(kKey), receiver(kKey);
  // Same microsecond, or the clock stepped back: still each one taken.
  for (std::int64_t t : {kNow, kNow, kNow - 500, kNow}) {
    EXPECT_EQ(Check(receiver, Signed(sender, t)), Verdict::kOk);
  }
}

TEST(MessageAuth, FirstMessageOfASenderMustBeWithinTheWindow) {
  MessageAuth sender(kKey), receiver(kKey);
  const std::int64_t old = kNow - MessageAuth::kWindowMicros - 1;
  EXPECT_EQ(Check(receiver, Signed(sender, old)), Verdict::kReplayed);
  MessageAuth future(kKey);
  EXPECT_EQ(
      Check(receiver, Signed(future, kNow + MessageAuth::kWindowMicros + 1)),
      Verdict::kReplayed);
  MessageAuth recent(kKey);
  EXPECT_EQ(Check(receiver, Signed(recent, kNow - 1'000'000)), Verdict::kOk);
}

TEST(MessageAuth, SendersAreTrackedApart) {
  MessageAuth a(kKey), b(kKey), receiver(kKey);
  ASSERT_NE(a.sender(), b.sender());
  EXPECT_EQ(Check(receiver, Signed(a, kNow + 100)), Verdict::kOk);
  // b's clock is behind a's: b's messages are not a's replays.
  EXPECT_EQ(Check(receiver, Signed(b, kNow)), Verdict::kOk);
}

TEST(MessageAuth, AcceptReplaysTakesOldStampsButNotForgeries) {
  MessageAuth sender(kKey), other("another key, just as long as it");
  MessageAuth player(kKey, /*accept_replays=*/true);
  const std::vector<std::uint8_t> m = Signed(sender, kNow - 3'600'000'000);
  EXPECT_EQ(Check(player, m), Verdict::kOk);
  EXPECT_EQ(Check(player, m), Verdict::kOk);
  EXPECT_EQ(Check(player, Payload()), Verdict::kUnsigned);
  EXPECT_EQ(Check(player, Signed(other)), Verdict::kForged);
}

TEST(MessageAuth, ShortKeyIsRefused) {
  EXPECT_THROW(MessageAuth("short"), std::invalid_argument);
}

class KeyFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("mrsim_key_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  std::string Path(const std::string& name) const {
    return (dir_ / name).string();
  }
  std::filesystem::path dir_;
};

TEST_F(KeyFile, KeygenWritesAPrivateKeyThatReadsBack) {
  const std::string path = Path("farm.key");
  WriteKeyFile(path);
  struct stat st {};
  ASSERT_EQ(stat(path.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0600u);
  const std::string key = ReadKeyFile(path);
  EXPECT_EQ(key.size(), 32u);
  WriteKeyFile(Path("other.key"));
  EXPECT_NE(ReadKeyFile(Path("other.key")), key);
}

TEST_F(KeyFile, KeygenRefusesToOverwrite) {
  const std::string path = Path("farm.key");
  WriteKeyFile(path);
  const std::string key = ReadKeyFile(path);
  EXPECT_THROW(WriteKeyFile(path), UsageError);
  EXPECT_EQ(ReadKeyFile(path), key);
}

TEST_F(KeyFile, KeyReadableByOthersIsRefusedNamingThePath) {
  const std::string path = Path("farm.key");
  WriteKeyFile(path);
  chmod(path.c_str(), 0644);
  try {
    ReadKeyFile(path);
    FAIL() << "a world-readable key was read";
  } catch (const UsageError& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("chmod 600"), std::string::npos);
  }
  chmod(path.c_str(), 0640);
  EXPECT_THROW(ReadKeyFile(path), UsageError);
}

TEST_F(KeyFile, MissingShortOrGarbledKeysAreRefused) {
  EXPECT_THROW(ReadKeyFile(Path("none.key")), UsageError);
  const auto write = [&](const std::string& name, const std::string& text) {
    std::ofstream(Path(name)) << text;
    chmod(Path(name).c_str(), 0600);
    return Path(name);
  };
  EXPECT_THROW(ReadKeyFile(write("short.key", "abcd\n")), UsageError);
  EXPECT_THROW(ReadKeyFile(write("text.key", std::string(64, 'z'))),
               UsageError);
  EXPECT_EQ(ReadKeyFile(write("ok.key", "# comment\n" + std::string(40, 'a'))),
            std::string(20, '\xaa'));
}

TEST_F(KeyFile, EnvironmentNamesTheKeyWhenNoFlagDoes) {
  const std::string path = Path("env.key");
  WriteKeyFile(path);
  setenv(kKeyFileEnv, path.c_str(), 1);
  const AuthConfig from_env = LoadAuthConfig("", false);
  unsetenv(kKeyFileEnv);
  EXPECT_TRUE(from_env.enabled());
  EXPECT_EQ(from_env.key_file, path);
  EXPECT_FALSE(LoadAuthConfig("", false).enabled());
}

}  // namespace
}  // namespace mrsim
