// What happened on one recorded channel, as the CSV and the MCAP logger
// count it and print it in their summaries.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mrsim {

struct ChannelStats {
  std::string channel;
  std::string type;  // full type name, or empty when unknown
  int64_t messages = 0;
  int64_t rows = 0;
  int64_t malformed = 0;     // bytes that are not a valid message
  int64_t unknown_type = 0;  // fingerprint not in the registry
  int64_t other_type = 0;    // a second type on a channel
  int64_t gaps = 0;
  int64_t missing = 0;
  int64_t back_jumps = 0;
  int64_t repeats = 0;  // re-sends skipped (see ChannelLedger)
  // Rows of yet another shape once the channel has Recorder::kMaxPartFiles
  // files: dropped, so decodable garbage cannot fill a folder.
  int64_t dropped = 0;
  bool has_seq = false;
  int64_t first_seq = 0;
  int64_t last_seq = 0;
  std::vector<std::string> files;
};

}  // namespace mrsim
