// The MCAP file format's constants (https://mcap.dev/spec): record
// opcodes, the magic, and the little-endian integers every record is made
// of. Shared by McapWriter and McapReader so both agree on every byte.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>

namespace mrsim::mcap {

// 0x89 "MCAP" '0' (major version 0) "\r\n", at the start and the end.
inline constexpr char kMagic[8] = {'\x89', 'M', 'C', 'A', 'P', '0', '\r', '\n'};
inline constexpr size_t kMagicSize = sizeof(kMagic);

enum class Op : uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kAttachment = 0x09,
  kAttachmentIndex = 0x0A,
  kStatistics = 0x0B,
  kMetadata = 0x0C,
  kMetadataIndex = 0x0D,
  kSummaryOffset = 0x0E,
  kDataEnd = 0x0F,
};

// opcode (1) + content length (8)
inline constexpr size_t kRecordPrefix = 9;
// A footer's content: summary_start, summary_offset_start, summary_crc.
inline constexpr size_t kFooterContent = 8 + 8 + 4;

// Appends little-endian integers and MCAP strings/bytes to a buffer.
class RecordBuffer {
 public:
  std::string& bytes() { return bytes_; }
  const std::string& bytes() const { return bytes_; }
  size_t size() const { return bytes_.size(); }
  void clear() { bytes_.clear(); }

  void U8(uint8_t v) { bytes_.push_back(static_cast<char>(v)); }
  void U16(uint16_t v) { Le(v, 2); }
  void U32(uint32_t v) { Le(v, 4); }
  void U64(uint64_t v) { Le(v, 8); }
  // uint32 length, then the bytes (String and Bytes alike).
  void Str(std::string_view s) {
    U32(static_cast<uint32_t>(s.size()));
    bytes_.append(s.data(), s.size());
  }
  void Raw(std::string_view s) { bytes_.append(s.data(), s.size()); }
  // Starts a record: opcode and a length filled in by EndRecord.
  size_t BeginRecord(Op op) {
    U8(static_cast<uint8_t>(op));
    const size_t at = bytes_.size();
    U64(0);
    return at;
  }
  void EndRecord(size_t at) { PutU64(at, bytes_.size() - at - 8); }
  // Overwrites 4 / 8 bytes at `at`.
  void PutU32(size_t at, uint32_t v) {
    for (int i = 0; i < 4; ++i)
      bytes_[at + i] = static_cast<char>(v >> (8 * i));
  }
  void PutU64(size_t at, uint64_t v) {
    for (int i = 0; i < 8; ++i)
      bytes_[at + i] = static_cast<char>(v >> (8 * i));
  }

 private:
  void Le(uint64_t v, int n) {
    char b[8];
    for (int i = 0; i < n; ++i) b[i] = static_cast<char>(v >> (8 * i));
    bytes_.append(b, n);
  }
  std::string bytes_;
};

// CRC-32 (zlib's, the one MCAP uses) of bytes, continuing from `crc`
// (start with 0).
uint32_t Crc32(uint32_t crc, const void* data, size_t size);

}  // namespace mrsim::mcap
