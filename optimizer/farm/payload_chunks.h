// Splitting the problem payload into chunks and putting it back together
// on a worker, whatever order the chunks arrive in and however often.
#pragma once

#include <string>
#include <vector>

namespace mrsim {

// Pieces of at most chunk_size bytes (one empty piece for an empty payload).
std::vector<std::string> SplitPayload(const std::string& payload,
                                      size_t chunk_size);

class ChunkAssembler {
 public:
  ChunkAssembler() = default;
  ChunkAssembler(int count, long long total_size);
  // Stores a chunk; false (and nothing stored) when the index or size does
  // not fit this payload. A repeated chunk is accepted and ignored.
  bool Add(int index, const std::string& data);
  // Up to `max` indices still missing, lowest first.
  std::vector<int> Missing(int max) const;
  bool complete() const { return received_ == count_; }
  int count() const { return count_; }
  int received() const { return received_; }
  // The payload (call when complete).
  std::string Join() const;

 private:
  int count_ = 0;
  long long total_size_ = 0;
  int received_ = 0;
  long long bytes_ = 0;  // received so far, never above total_size_
  std::vector<std::string> chunks_;
  std::vector<bool> have_;
};

}  // namespace mrsim
