// Writes an indexed MCAP file (https://mcap.dev/spec) that Foxglove,
// PlotJuggler and the mcap tools open: the header, then the messages in
// zstd-compressed chunks, each followed by its message indexes, and at
// Finish() the summary (schemas, channels, statistics, chunk indexes), its
// offsets and the footer, with CRC-32s of every chunk, the data section
// and the summary.
//
// Crash safety: a chunk is written whole, with one write(2), by
// CloseChunk(); the bytes of a closed chunk are in the file even if the
// process is killed right after, so a file whose writer died reads (with a
// streaming reader) up to its last closed chunk. The caller closes chunks
// as often as it wants to lose at most; a chunk also closes by itself when
// it holds options.chunk_size bytes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "logger/mcap/mcap_format.h"

namespace mrsim::mcap {

// How chunks are stored. Every MCAP reader reads both (the spec requires
// uncompressed chunks; zstd is the format's standard compression).
enum class ChunkCompression {
  kZstd,  // about 7x smaller on mrsim JSON, for most of the writer's CPU
  kNone,  // no compression CPU; the file is about 2.4x the .lcmlog
};

struct McapWriterOptions {
  std::string profile;  // "" : none of the well-known profiles
  std::string library = "mrsim";
  // Uncompressed bytes after which a chunk is closed by itself.
  size_t chunk_size = 1 << 20;
  ChunkCompression compression = ChunkCompression::kZstd;
  int zstd_level = 1;  // the fastest standard level: about 6x on mrsim JSON
};

class McapWriter {
 public:
  // Creates (or truncates) path and writes the magic and header. Throws
  // std::runtime_error naming the file.
  explicit McapWriter(const std::string& path, McapWriterOptions options = {});
  // Finishes the file if Finish() was not called (errors are lost then).
  ~McapWriter();
  McapWriter(const McapWriter&) = delete;
  McapWriter& operator=(const McapWriter&) = delete;

  // A schema (id 1, 2, ...; 0 means none). encoding e.g. "jsonschema".
  uint16_t AddSchema(std::string_view name, std::string_view encoding,
                     std::string_view data);
  // A channel (id 0, 1, ...) on `topic` whose messages are in
  // `message_encoding` (e.g. "json") of schema `schema_id`. At most 65535
  // channels; throws std::length_error past that.
  uint16_t AddChannel(uint16_t schema_id, std::string_view topic,
                      std::string_view message_encoding);
  // One message. Times in nanoseconds. Throws std::runtime_error when a
  // chunk it closes cannot be written.
  void WriteMessage(uint16_t channel_id, uint32_t sequence, uint64_t log_time,
                    uint64_t publish_time, std::string_view data);
  // Compresses and writes the open chunk with its message indexes; nothing
  // when it is empty.
  void CloseChunk();
  // Closes the chunk, writes the summary and footer and closes the file.
  // Throws std::runtime_error naming the file. Later calls do nothing.
  void Finish();

  // Messages in the open chunk, and the log time of its first one.
  size_t chunk_messages() const { return chunk_messages_; }
  uint64_t chunk_start_time() const { return chunk_start_; }
  int64_t chunks() const { return static_cast<int64_t>(chunk_indexes_.size()); }
  uint64_t messages() const { return message_count_; }
  const std::string& path() const { return path_; }

 private:
  struct ChunkIndex {
    uint64_t start_time, end_time, offset, length;
    std::vector<std::pair<uint16_t, uint64_t>> index_offsets;
    uint64_t index_length, compressed_size, uncompressed_size;
  };
  // Appends bytes to the file (and the data CRC while in the data section).
  void Write(const std::string& bytes);
  // Appends the pieces in order with one writev(2) (as one write: a chunk
  // is in the file whole or cut off at its end).
  void WriteAll(const std::string_view* pieces, size_t count);

  std::string path_;
  McapWriterOptions options_;
  int fd_ = -1;
  void* zstd_ = nullptr;  // ZSTD_CCtx
  bool finished_ = false;
  bool broken_ = false;  // a write failed: nothing more is written
  uint64_t offset_ = 0;  // bytes written
  uint32_t data_crc_ = 0;

  std::vector<std::string> schema_records_;   // for the summary
  std::vector<std::string> channel_records_;  // for the summary
  std::vector<uint64_t> channel_counts_;

  RecordBuffer chunk_;  // the open chunk's records, uncompressed
  size_t chunk_messages_ = 0;
  uint64_t chunk_start_ = 0, chunk_end_ = 0;
  // Per channel: (log_time, offset in chunk_) of this chunk's messages.
  std::vector<std::vector<std::pair<uint64_t, uint64_t>>> chunk_index_;
  std::vector<uint16_t> chunk_channels_;  // channels with messages in it
  std::string compressed_;
  RecordBuffer out_;
  RecordBuffer indexes_;  // the closing chunk's message indexes

  std::vector<ChunkIndex> chunk_indexes_;
  uint64_t message_count_ = 0;
  uint64_t start_time_ = 0, end_time_ = 0;
};

}  // namespace mrsim::mcap
