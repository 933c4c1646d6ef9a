// Turns encoded LCM messages of one type into CSV rows with named columns.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace mrsim {

// One message as a CSV row.
struct FlatRow {
  std::string values;  // cells joined by ',', no line break
  bool has_seq = false;
  int64_t seq = 0;
  // The message's top-level `sender` string when it has one: senders
  // sharing a channel (a controller and mrsim-camera's lockstep answers on
  // a command channel) number their messages each on their own.
  std::string sender;
};

class MessageFlattener {
 public:
  virtual ~MessageFlattener() = default;
  // Decodes one whole message (fingerprint included) into row, replacing
  // its values (whatever they held before; the recorder hands back other
  // rows' buffers). Returns false when the bytes are not a well-formed
  // message of this type; never throws.
  virtual bool Flatten(const uint8_t* data, size_t size, FlatRow* row) = 0;
  virtual std::string type_name() const = 0;

  // Column names of the last row flattened. They change only when the
  // message's shape (its array lengths) changes, which bumps shape_version.
  const std::vector<std::string>& columns() const { return columns_; }
  uint64_t shape_version() const { return shape_version_; }

 protected:
  void SetColumns(std::vector<std::string> columns) {
    columns_ = std::move(columns);
    ++shape_version_;
  }

 private:
  std::vector<std::string> columns_;
  uint64_t shape_version_ = 0;
};

}  // namespace mrsim
