// Reads an MCAP file (https://mcap.dev/spec) record by record from its
// bytes, as mrsim-log writes them and as any writer may: every length is
// checked against the bytes left before it is used, a chunk's
// uncompressed size against kMaxChunkSize before anything is allocated,
// and the CRCs of chunks, the data section and the summary are checked
// where the file has them. A file cut off after its last whole record (a
// writer that was killed) reads up to there and says it is not complete;
// anything else malformed throws McapError naming the byte offset.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>

namespace mrsim::mcap {

class McapError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct McapSchema {
  uint16_t id = 0;
  std::string name, encoding, data;
};

struct McapChannel {
  uint16_t id = 0;
  uint16_t schema_id = 0;
  std::string topic, message_encoding;
};

// One message; `data` points into the reader's buffers and is valid only
// during the callback.
struct McapMessage {
  const McapChannel* channel = nullptr;
  const McapSchema* schema = nullptr;  // the channel's; null for schema 0
  uint32_t sequence = 0;
  uint64_t log_time = 0;  // ns
  uint64_t publish_time = 0;
  std::string_view data;
};

struct McapSummary {
  std::map<uint16_t, McapSchema> schemas;
  std::map<uint16_t, McapChannel> channels;
  int64_t messages = 0;
  int64_t chunks = 0;
  // Footer and closing magic read (and the summary CRC right): the writer
  // finished. False for a file cut off after its last whole record.
  bool complete = false;
};

// The largest chunk (uncompressed) accepted: far above the 1 MiB chunks
// mrsim-log writes, far below what would exhaust memory.
inline constexpr uint64_t kMaxChunkSize = uint64_t{256} << 20;

// Reads `bytes` (a whole file, or the start of one), calling on_message
// for every message in file order. `name` names the file in errors.
McapSummary ReadMcap(std::string_view bytes, const std::string& name,
                     const std::function<void(const McapMessage&)>& on_message);

}  // namespace mrsim::mcap
