// Walks an encoded LCM message without decoding it, for the checks that
// lcmtypes/wire_check_gen.py generates (mrsim/wire_check.hpp): every length
// is checked against the bytes left and the field's declared maximum before
// anything is skipped, so a forged length can neither read past the buffer
// nor make lcm-gen's decode allocate more than the message could hold.
// Allocates nothing: a refused message costs a walk, never memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>

namespace mrsim {

// Why bytes were refused: the field ("robot_state_t.num_modules") and what
// was wrong with it. Static strings, so reporting allocates nothing.
struct WireError {
  const char* field = "";
  const char* problem = "";
};

// True when `data` holds exactly one encoded Message (its fingerprint first)
// whose every length lcm-gen's decode may trust. Specialised for each type
// in mrsim/wire_check.hpp.
template <class Message>
bool CheckWire(const void* data, size_t size, WireError* error);
// Empties the arrays of a decoded message whose length is 0: lcm-gen's
// decode leaves them as they were, so a message decoded into a reused one
// would keep the last message's elements (generated in wire_check.hpp).
template <class Message>
void ClearEmptyArrays(Message* msg);

class WireReader {
 public:
  WireReader(const uint8_t* data, size_t size, WireError* error)
      : p_(data), left_(size), error_(error) {}

  bool Fail(const char* field, const char* problem) {
    if (error_ != nullptr) {
      error_->field = field;
      error_->problem = problem;
    }
    return false;
  }

  bool Skip(size_t bytes, const char* field) {
    if (bytes > left_) return Fail(field, "ends before the field does");
    p_ += bytes;
    left_ -= bytes;
    return true;
  }

  // A big-endian two's-complement integer of `bytes` (1, 2, 4 or 8) bytes.
  bool Integer(size_t bytes, int64_t* value, const char* field) {
    if (bytes > left_) return Fail(field, "ends before the field does");
    uint64_t v = 0;
    for (size_t k = 0; k < bytes; ++k) v = (v << 8) | p_[k];
    switch (bytes) {
      case 1:
        *value = static_cast<int8_t>(static_cast<uint8_t>(v));
        break;
      case 2:
        *value = static_cast<int16_t>(static_cast<uint16_t>(v));
        break;
      case 4:
        *value = static_cast<int32_t>(static_cast<uint32_t>(v));
        break;
      default:
        *value = static_cast<int64_t>(v);
        break;
    }
    p_ += bytes;
    left_ -= bytes;
    return true;
  }

  // LCM's string: an int32 length counting the terminating NUL, then the
  // bytes. At most `max_length` bytes of text, no NUL before the end.
  bool String(int64_t max_length, const char* field) {
    int64_t length = 0;
    if (!Integer(4, &length, field)) return false;
    if (length < 1) return Fail(field, "string length below 1 (counts NUL)");
    if (length - 1 > max_length) return Fail(field, "string over its maximum");
    if (static_cast<uint64_t>(length) > left_) {
      return Fail(field, "string length beyond the message");
    }
    // One NUL, at the end: what C and every other LCM language read, and
    // what re-encodes to the same bytes (a path cut short by a NUL is not).
    const size_t text = static_cast<size_t>(length) - 1;
    if (p_[text] != 0 || std::memchr(p_, 0, text) != nullptr) {
      return Fail(field, "string not ended by its only NUL");
    }
    p_ += length;
    left_ -= static_cast<size_t>(length);
    return true;
  }

  // An array length, before its elements (each at least `min_element`
  // bytes) are walked: 0..max and not more than the bytes left can hold.
  bool Count(int64_t count, int64_t max, size_t min_element,
             const char* field) {
    if (count < 0) return Fail(field, "negative array length");
    if (count > max) return Fail(field, "array length over its maximum");
    // count <= max < 2^31 and min_element is small: no overflow.
    if (static_cast<uint64_t>(count) * min_element > left_) {
      return Fail(field, "array length beyond the message");
    }
    return true;
  }

  bool Fingerprint(int64_t expected, const char* type) {
    int64_t hash = 0;
    if (!Integer(8, &hash, type)) return false;
    if (hash != expected) return Fail(type, "fingerprint of another type");
    return true;
  }

  bool AtEnd(const char* type) {
    return left_ == 0 || Fail(type, "bytes after the end of the message");
  }

 private:
  const uint8_t* p_;
  size_t left_;
  WireError* error_;
};

}  // namespace mrsim
