#include "optimizer/farm/payload_chunks.h"

#include <stdexcept>

namespace mrsim {

std::vector<std::string> SplitPayload(const std::string& payload,
                                      size_t chunk_size) {
  if (chunk_size == 0) throw std::invalid_argument("chunk size must be > 0");
  std::vector<std::string> chunks;
  for (size_t pos = 0; pos < payload.size(); pos += chunk_size) {
    chunks.push_back(payload.substr(pos, chunk_size));
  }
  if (chunks.empty()) chunks.emplace_back();
  return chunks;
}

ChunkAssembler::ChunkAssembler(int count, long long total_size)
    : count_(count),
      total_size_(total_size),
      chunks_(count > 0 ? count : 0),
      have_(count > 0 ? count : 0, false) {}

bool ChunkAssembler::Add(int index, const std::string& data) {
  if (index < 0 || index >= count_) return false;
  if (have_[index]) return true;
  // Chunks that add up to more than the announced payload are forged.
  if (static_cast<long long>(data.size()) > total_size_ - bytes_) return false;
  bytes_ += static_cast<long long>(data.size());
  chunks_[index] = data;
  have_[index] = true;
  ++received_;
  return true;
}

std::vector<int> ChunkAssembler::Missing(int max) const {
  std::vector<int> missing;
  for (int i = 0; i < count_ && static_cast<int>(missing.size()) < max; ++i) {
    if (!have_[i]) missing.push_back(i);
  }
  return missing;
}

std::string ChunkAssembler::Join() const {
  std::string out;
  out.reserve(static_cast<size_t>(total_size_));
  for (const std::string& c : chunks_) out += c;
  return out;
}

}  // namespace mrsim
