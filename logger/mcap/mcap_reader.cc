#include "logger/mcap/mcap_reader.h"

#include <zstd.h>

#include <cstring>
#include <string>

#include "logger/mcap/mcap_format.h"

namespace mrsim::mcap {
namespace {

// Reads fields of one record's content; every read is checked against the
// bytes left in it.
class Fields {
 public:
  Fields(std::string_view bytes, uint64_t offset, const std::string& name)
      : bytes_(bytes), offset_(offset), name_(name) {}

  uint8_t U8() { return static_cast<uint8_t>(Take(1)[0]); }
  uint16_t U16() { return static_cast<uint16_t>(Le(Take(2))); }
  uint32_t U32() { return static_cast<uint32_t>(Le(Take(4))); }
  uint64_t U64() { return Le(Take(8)); }
  std::string_view Str(const char* what) {
    const uint32_t n = U32();
    if (n > left())
      Fail(std::string(what) + " of " + std::to_string(n) +
           " bytes runs past its record");
    return Take(n);
  }
  std::string_view Rest() { return Take(left()); }
  size_t left() const { return bytes_.size() - at_; }
  [[noreturn]] void Fail(const std::string& what) const {
    throw McapError(name_ + ": byte " + std::to_string(offset_ + at_) + ": " +
                    what);
  }

 private:
  std::string_view Take(size_t n) {
    if (n > left()) Fail("record too short for its fields");
    const std::string_view out = bytes_.substr(at_, n);
    at_ += n;
    return out;
  }
  static uint64_t Le(std::string_view b) {
    uint64_t v = 0;
    for (size_t i = b.size(); i-- > 0;) {
      v = (v << 8) | static_cast<uint8_t>(b[i]);
    }
    return v;
  }
  std::string_view bytes_;
  size_t at_ = 0;
  uint64_t offset_;
  const std::string& name_;
};

class Reader {
 public:
  Reader(const std::string& name,
         const std::function<void(const McapMessage&)>& on_message)
      : name_(name), on_message_(on_message) {}

  McapSummary Read(std::string_view file) {
    if (file.size() < kMagicSize ||
        std::memcmp(file.data(), kMagic, kMagicSize) != 0) {
      throw McapError(name_ +
                      ": not an MCAP file (no MCAP magic at its start)");
    }
    uint64_t at = kMagicSize;
    bool first = true;
    while (at < file.size()) {
      if (file.size() - at < kRecordPrefix) return summary_;  // cut off
      const auto op = static_cast<uint8_t>(file[at]);
      uint64_t length = 0;
      for (int i = 7; i >= 0; --i) {
        length = (length << 8) | static_cast<uint8_t>(file[at + 1 + i]);
      }
      if (length > file.size() - at - kRecordPrefix) return summary_;
      const std::string_view content = file.substr(at + kRecordPrefix, length);
      Fields f(content, at + kRecordPrefix, name_);
      if (first && op != static_cast<uint8_t>(Op::kHeader)) {
        f.Fail("the first record is not a Header");
      }
      first = false;
      if (op == static_cast<uint8_t>(Op::kDataEnd)) {
        const uint32_t crc = f.U32();
        if (crc != 0 && crc != Crc32(0, file.data(), at)) {
          f.Fail("data section CRC does not match");
        }
        in_summary_ = true;
      } else if (op == static_cast<uint8_t>(Op::kFooter)) {
        const uint64_t summary_start = f.U64();
        f.U64();  // summary_offset_start
        const uint64_t crc_end = at + kRecordPrefix + 16;
        const uint32_t crc = f.U32();
        // The summary CRC runs from the summary's start (or, with none,
        // from the footer) through summary_offset_start.
        const uint64_t crc_start =
            summary_start > 0 && summary_start <= at ? summary_start : at;
        if (crc != 0 &&
            crc != Crc32(0, file.data() + crc_start, crc_end - crc_start)) {
          f.Fail("summary CRC does not match");
        }
        const uint64_t end = at + kRecordPrefix + length;
        if (file.size() - end < kMagicSize) return summary_;
        if (std::memcmp(file.data() + end, kMagic, kMagicSize) != 0) {
          f.Fail("no MCAP magic after the footer");
        }
        summary_.complete = true;
        return summary_;
      } else {
        if (!in_summary_) Record(op, f);
      }
      at += kRecordPrefix + length;
    }
    return summary_;
  }

 private:
  void Record(uint8_t op, Fields& f) {
    switch (static_cast<Op>(op)) {
      case Op::kSchema: {
        McapSchema s;
        s.id = f.U16();
        s.name = f.Str("schema name");
        s.encoding = f.Str("schema encoding");
        s.data = f.Str("schema data");
        if (s.id == 0) f.Fail("schema id 0 is reserved");
        summary_.schemas[s.id] = std::move(s);
        break;
      }
      case Op::kChannel: {
        McapChannel c;
        c.id = f.U16();
        c.schema_id = f.U16();
        c.topic = f.Str("topic");
        c.message_encoding = f.Str("message encoding");
        f.Str("metadata");
        if (c.schema_id != 0 && summary_.schemas.count(c.schema_id) == 0) {
          f.Fail("channel " + c.topic + " names schema " +
                 std::to_string(c.schema_id) + ", not defined before it");
        }
        summary_.channels[c.id] = std::move(c);
        break;
      }
      case Op::kMessage: {
        McapMessage m;
        const uint16_t channel = f.U16();
        const auto it = summary_.channels.find(channel);
        if (it == summary_.channels.end()) {
          f.Fail("message on channel " + std::to_string(channel) +
                 ", not defined before it");
        }
        m.channel = &it->second;
        if (m.channel->schema_id != 0) {
          const auto schema = summary_.schemas.find(m.channel->schema_id);
          if (schema != summary_.schemas.end()) m.schema = &schema->second;
        }
        m.sequence = f.U32();
        m.log_time = f.U64();
        m.publish_time = f.U64();
        m.data = f.Rest();
        ++summary_.messages;
        on_message_(m);
        break;
      }
      case Op::kChunk:
        Chunk(f);
        break;
      case Op::kHeader:
        f.Str("profile");
        f.Str("library");
        break;
      default:
        break;  // indexes, attachments, metadata: not needed to read
    }
  }

  void Chunk(Fields& f) {
    f.U64();  // message_start_time
    f.U64();  // message_end_time
    const uint64_t size = f.U64();
    const uint32_t crc = f.U32();
    const std::string compression(f.Str("compression"));
    const uint64_t packed_size = f.U64();
    if (packed_size != f.left()) {
      f.Fail("chunk records of " + std::to_string(packed_size) +
             " bytes, its record holds " + std::to_string(f.left()));
    }
    if (size > kMaxChunkSize) {
      f.Fail("chunk of " + std::to_string(size) + " bytes uncompressed, over " +
             std::to_string(kMaxChunkSize));
    }
    const std::string_view packed = f.Rest();
    std::string_view records;
    if (compression.empty()) {
      if (packed.size() != size) f.Fail("uncompressed chunk of the wrong size");
      records = packed;
    } else if (compression == "zstd") {
      chunk_.resize(size);
      const size_t got = ZSTD_decompress(chunk_.data(), chunk_.size(),
                                         packed.data(), packed.size());
      if (ZSTD_isError(got) || got != size) {
        f.Fail("zstd chunk does not decompress to its " + std::to_string(size) +
               " bytes");
      }
      records = std::string_view(chunk_.data(), size);
    } else {
      f.Fail("chunk compression '" + compression + "' is not supported");
    }
    if (crc != 0 && crc != Crc32(0, records.data(), records.size())) {
      f.Fail("chunk CRC does not match its records");
    }
    ++summary_.chunks;
    uint64_t at = 0;
    while (at < records.size()) {
      if (records.size() - at < kRecordPrefix) {
        f.Fail("a record in a chunk is cut off");
      }
      const auto op = static_cast<uint8_t>(records[at]);
      uint64_t length = 0;
      for (int i = 7; i >= 0; --i) {
        length = (length << 8) | static_cast<uint8_t>(records[at + 1 + i]);
      }
      if (length > records.size() - at - kRecordPrefix) {
        f.Fail("a record in a chunk runs past it");
      }
      if (op == static_cast<uint8_t>(Op::kChunk)) {
        f.Fail("a chunk inside a chunk");
      }
      Fields inner(records.substr(at + kRecordPrefix, length), at, name_);
      Record(op, inner);
      at += kRecordPrefix + length;
    }
  }

  const std::string& name_;
  const std::function<void(const McapMessage&)>& on_message_;
  McapSummary summary_;
  std::string chunk_;
  bool in_summary_ = false;
};

}  // namespace

McapSummary ReadMcap(
    std::string_view bytes, const std::string& name,
    const std::function<void(const McapMessage&)>& on_message) {
  return Reader(name, on_message).Read(bytes);
}

}  // namespace mrsim::mcap
