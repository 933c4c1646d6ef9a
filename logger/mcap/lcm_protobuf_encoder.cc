#include "logger/mcap/lcm_protobuf_encoder.h"

#include <algorithm>
#include <cstring>
#include <map>
#include <stdexcept>

namespace mrsim {
namespace {

// As the CSV logger's layout: no array holds more elements than this.
constexpr int64_t kMaxElements = int64_t{1} << 26;

enum class Kind : uint8_t {
  kInt8,
  kInt16,
  kInt32,
  kInt64,
  kByte,
  kBool,
  kFloat,
  kDouble,
  kString,
  kStruct
};

Kind KindOf(const std::string& type) {
  if (type == "int8_t") return Kind::kInt8;
  if (type == "int16_t") return Kind::kInt16;
  if (type == "int32_t") return Kind::kInt32;
  if (type == "int64_t") return Kind::kInt64;
  if (type == "byte") return Kind::kByte;
  if (type == "boolean") return Kind::kBool;
  if (type == "float") return Kind::kFloat;
  if (type == "double") return Kind::kDouble;
  if (type == "string") return Kind::kString;
  return Kind::kStruct;
}

// Encoded LCM bytes of one element; strings and structs take at least this.
size_t LcmSize(Kind k) {
  switch (k) {
    case Kind::kInt16:
      return 2;
    case Kind::kInt32:
    case Kind::kFloat:
    case Kind::kString:
      return 4;
    case Kind::kInt64:
    case Kind::kDouble:
      return 8;
    default:
      return 1;
  }
}

constexpr uint32_t kVarint = 0, kFixed64 = 1, kLengthDelimited = 2,
                   kFixed32 = 5;

uint32_t Tag(uint32_t field, uint32_t wire) { return (field << 3) | wire; }

// Length of the valid UTF-8 sequence at p (1-4), or 0 when it is not one:
// JsonWriter::String's rule, so both encodings give the same text.
size_t Utf8Length(const uint8_t* p, const uint8_t* end) {
  const uint8_t c = p[0];
  size_t n = 0;
  uint32_t min = 0;
  uint32_t v = 0;
  if (c < 0x80) return 1;
  if ((c & 0xE0) == 0xC0) {
    n = 2, min = 0x80, v = c & 0x1F;
  } else if ((c & 0xF0) == 0xE0) {
    n = 3, min = 0x800, v = c & 0x0F;
  } else if ((c & 0xF8) == 0xF0) {
    n = 4, min = 0x10000, v = c & 0x07;
  } else {
    return 0;
  }
  if (static_cast<size_t>(end - p) < n) return 0;
  for (size_t i = 1; i < n; ++i) {
    if ((p[i] & 0xC0) != 0x80) return 0;
    v = (v << 6) | (p[i] & 0x3F);
  }
  if (v < min || v > 0x10FFFF || (v >= 0xD800 && v <= 0xDFFF)) return 0;
  return n;
}

}  // namespace

struct LcmProtobufEncoder::Layout {
  struct Dim {
    int64_t fixed = -1;  // constant size, or -1
    int ref = -1;        // index of the member holding the size
  };
  struct Member {
    Kind kind = Kind::kStruct;
    uint32_t field = 0;  // protobuf field number: declaration order + 1
    const Layout* child = nullptr;
    std::vector<Dim> dims;
    bool seq = false;  // the top-level int64_t seq
  };
  std::vector<Member> members;
};

namespace {

using Layout = LcmProtobufEncoder::Layout;

// One message's walk: reads LCM (big-endian) and appends protobuf.
class Run {
 public:
  Run(const uint8_t* data, size_t size, std::string* buf, size_t* out_size)
      : p_(data),
        left_(size),
        buf_(*buf),
        size_(*out_size),
        limit_(16 * size + 65536) {}

  bool has_seq = false;
  int64_t seq = 0;
  size_t left() const { return left_; }

  bool Struct(const Layout& s, int depth) {
    if (depth > LcmProtobufEncoder::kMaxDepth) return false;
    const size_t base = ints_.size();
    ints_.resize(base + s.members.size(), 0);
    bool ok = true;
    for (size_t mi = 0; ok && mi < s.members.size(); ++mi) {
      const Layout::Member& m = s.members[mi];
      ok = m.dims.empty() ? Scalar(m, &ints_[base + mi], depth)
                          : Array(m, base, depth);
    }
    ints_.resize(base);
    return ok;
  }

 private:
  // ---- reading LCM
  bool Take(size_t n, const uint8_t** at) {
    if (n > left_) return false;
    *at = p_;
    p_ += n;
    left_ -= n;
    return true;
  }
  static uint64_t Be(const uint8_t* b, size_t n) {
    uint64_t v = 0;
    for (size_t k = 0; k < n; ++k) v = (v << 8) | b[k];
    return v;
  }
  // A fixed-size number's value, sign-extended for the signed kinds.
  static int64_t IntValue(Kind k, const uint8_t* b) {
    switch (k) {
      case Kind::kInt8:
        return static_cast<int8_t>(b[0]);
      case Kind::kInt16:
        return static_cast<int16_t>(Be(b, 2));
      case Kind::kInt32:
        return static_cast<int32_t>(Be(b, 4));
      case Kind::kInt64:
        return static_cast<int64_t>(Be(b, 8));
      case Kind::kBool:
        return b[0] != 0 ? 1 : 0;
      default:  // byte
        return b[0];
    }
  }

  // ---- writing protobuf
  bool Room(size_t n) {
    if (size_ + n > limit_) return false;
    if (size_ + n > buf_.size()) {
      buf_.resize(std::max(buf_.size() * 2, size_ + n + 4096));
    }
    return true;
  }
  void Varint(uint64_t v) {
    char* out = buf_.data() + size_;
    while (v >= 0x80) {
      *out++ = static_cast<char>(v | 0x80);
      v >>= 7;
    }
    *out++ = static_cast<char>(v);
    size_ = static_cast<size_t>(out - buf_.data());
  }
  // Copies n big-endian bytes as little-endian.
  void Swapped(const uint8_t* b, size_t n) {
    char* out = buf_.data() + size_;
    for (size_t k = 0; k < n; ++k) out[k] = static_cast<char>(b[n - 1 - k]);
    size_ += n;
  }
  // A varint of a number of this kind: sint32 zigzag for int8-32, int64
  // as is, byte and bool as uint32.
  static uint64_t WireValue(Kind k, int64_t v) {
    switch (k) {
      case Kind::kInt8:
      case Kind::kInt16:
      case Kind::kInt32: {
        const auto v32 = static_cast<int32_t>(v);
        return (static_cast<uint32_t>(v32) << 1) ^
               static_cast<uint32_t>(v32 >> 31);
      }
      default:
        return static_cast<uint64_t>(v);
    }
  }
  // Starts a length-delimited field with one byte kept for its length;
  // End moves the contents up when the length needs more.
  bool Begin(uint32_t tag, size_t* start) {
    if (!Room(16)) return false;
    Varint(tag);
    ++size_;
    *start = size_;
    return true;
  }
  bool End(size_t start) {
    const size_t len = size_ - start;
    if (len < 0x80) {
      buf_[start - 1] = static_cast<char>(len);
      return true;
    }
    size_t n = 1;
    for (size_t v = len; v >= 0x80; v >>= 7) ++n;
    if (!Room(n)) return false;
    std::memmove(buf_.data() + start - 1 + n, buf_.data() + start, len);
    size_ = start - 1;
    Varint(len);
    size_ += len;
    return true;
  }

  // A string's bytes (after its length, before its NUL), valid UTF-8.
  bool StringBytes(uint32_t tag, bool skip_empty) {
    const uint8_t* at = nullptr;
    if (!Take(4, &at)) return false;
    const auto len = static_cast<int32_t>(Be(at, 4));
    if (len < 1 || static_cast<size_t>(len) > left_) return false;
    const uint8_t* s = nullptr;
    Take(static_cast<size_t>(len), &s);
    if (s[len - 1] != 0) return false;
    const size_t n = static_cast<size_t>(len) - 1;
    if (n == 0 && skip_empty) return true;
    size_t start = 0;
    // U+FFFD is 3 bytes for each byte replaced.
    if (!Begin(tag, &start) || !Room(3 * n)) return false;
    char* out = buf_.data() + size_;
    const uint8_t* end = s + n;
    while (s < end) {
      if (*s < 0x80) {
        *out++ = static_cast<char>(*s++);
        continue;
      }
      const size_t k = Utf8Length(s, end);
      if (k == 0) {
        std::memcpy(out, "\xEF\xBF\xBD", 3);
        out += 3;
        ++s;
      } else {
        std::memcpy(out, s, k);
        out += k;
        s += k;
      }
    }
    size_ = static_cast<size_t>(out - buf_.data());
    return End(start);
  }

  bool Scalar(const Layout::Member& m, int64_t* int_value, int depth) {
    const uint32_t f = m.field;
    const uint8_t* b = nullptr;
    switch (m.kind) {
      case Kind::kString:
        return StringBytes(Tag(f, kLengthDelimited), true);
      case Kind::kStruct: {
        size_t start = 0;
        return Begin(Tag(f, kLengthDelimited), &start) &&
               Struct(*m.child, depth + 1) && End(start);
      }
      case Kind::kFloat:
      case Kind::kDouble: {
        const size_t n = LcmSize(m.kind);
        if (!Take(n, &b)) return false;
        if (Be(b, n) == 0) return true;  // +0.0: the default
        if (!Room(16)) return false;
        Varint(Tag(f, n == 8 ? kFixed64 : kFixed32));
        Swapped(b, n);
        return true;
      }
      default: {
        if (!Take(LcmSize(m.kind), &b)) return false;
        const int64_t v = IntValue(m.kind, b);
        *int_value = v;
        if (m.seq) {
          has_seq = true;
          seq = v;
        }
        if (v == 0) return true;
        if (!Room(16)) return false;
        Varint(Tag(f, kVarint));
        Varint(WireValue(m.kind, v));
        return true;
      }
    }
  }

  bool Array(const Layout::Member& m, size_t base, int depth) {
    int64_t dims[8];
    std::vector<int64_t> many;
    int64_t* d = dims;
    if (m.dims.size() > 8) {
      many.resize(m.dims.size());
      d = many.data();
    }
    int64_t count = 1;
    for (size_t i = 0; i < m.dims.size(); ++i) {
      const Layout::Dim& dim = m.dims[i];
      const int64_t n = dim.ref >= 0 ? ints_[base + dim.ref] : dim.fixed;
      if (n < 0 || n > kMaxElements) return false;
      d[i] = n;
      count *= n;
      if (count > kMaxElements) return false;
    }
    if (static_cast<uint64_t>(count) * LcmSize(m.kind) > left_) return false;
    return Rows(m, d, m.dims.size(), m.field, depth);
  }

  // The elements of `ndims` dimensions as field `field`: the last one as a
  // packed (or bytes, or repeated) field, each row of the others as a
  // wrapper message whose field 1 holds the row.
  bool Rows(const Layout::Member& m, const int64_t* d, size_t ndims,
            uint32_t field, int depth) {
    if (ndims > 1) {
      for (int64_t i = 0; i < d[0]; ++i) {
        size_t start = 0;
        if (!Begin(Tag(field, kLengthDelimited), &start) ||
            !Rows(m, d + 1, ndims - 1, 1, depth) || !End(start)) {
          return false;
        }
      }
      return true;
    }
    const int64_t n = d[0];
    const uint32_t tag = Tag(field, kLengthDelimited);
    switch (m.kind) {
      case Kind::kString:
        for (int64_t i = 0; i < n; ++i) {
          if (!StringBytes(tag, false)) return false;
        }
        return true;
      case Kind::kStruct:
        for (int64_t i = 0; i < n; ++i) {
          size_t start = 0;
          if (!Begin(tag, &start) || !Struct(*m.child, depth + 1) ||
              !End(start)) {
            return false;
          }
        }
        return true;
      default:
        break;
    }
    if (n == 0) return true;  // an empty repeated field: nothing written
    const size_t elem = LcmSize(m.kind);
    const uint8_t* b = nullptr;
    Take(static_cast<size_t>(n) * elem, &b);  // Array checked the bytes
    const auto count = static_cast<size_t>(n);
    if (m.kind == Kind::kByte) {
      if (!Room(16 + count)) return false;
      Varint(tag);
      Varint(count);
      std::memcpy(buf_.data() + size_, b, count);
      size_ += count;
      return true;
    }
    if (m.kind == Kind::kDouble || m.kind == Kind::kFloat) {
      if (!Room(16 + count * elem)) return false;
      Varint(tag);
      Varint(count * elem);
      char* out = buf_.data() + size_;
      if (elem == 8) {
        for (size_t i = 0; i < count; ++i, b += 8, out += 8) {
          uint64_t v = 0;
          std::memcpy(&v, b, 8);
          v = __builtin_bswap64(v);
          std::memcpy(out, &v, 8);
        }
      } else {
        for (size_t i = 0; i < count; ++i, b += 4, out += 4) {
          uint32_t v = 0;
          std::memcpy(&v, b, 4);
          v = __builtin_bswap32(v);
          std::memcpy(out, &v, 4);
        }
      }
      size_ += count * elem;
      return true;
    }
    size_t start = 0;
    if (!Begin(tag, &start) || !Room(count * 10)) return false;
    for (size_t i = 0; i < count; ++i, b += elem) {
      Varint(WireValue(m.kind, IntValue(m.kind, b)));
    }
    return End(start);
  }

  const uint8_t* p_;
  size_t left_;
  std::string& buf_;
  size_t& size_;
  size_t limit_;
  std::vector<int64_t> ints_;
};

}  // namespace

LcmProtobufEncoder::LcmProtobufEncoder(const LcmTypeRegistry& registry,
                                       const LcmStruct& type)
    : type_name_(type.full_name()), fingerprint_(registry.Fingerprint(type)) {
  std::map<std::string, Layout*> compiled;
  // Structs are compiled once each, children after their parents; a struct
  // that contains itself (through an array) points back to its layout.
  std::vector<std::pair<const LcmStruct*, Layout*>> todo;
  const auto layout_of = [&](const LcmStruct& s) {
    auto it = compiled.find(s.full_name());
    if (it != compiled.end()) return it->second;
    layouts_.push_back(std::make_unique<Layout>());
    Layout* l = layouts_.back().get();
    compiled[s.full_name()] = l;
    todo.emplace_back(&s, l);
    return l;
  };
  layout_of(type);
  for (size_t t = 0; t < todo.size(); ++t) {
    const LcmStruct& s = *todo[t].first;
    Layout* l = todo[t].second;
    for (size_t i = 0; i < s.members.size(); ++i) {
      const LcmMember& src = s.members[i];
      Layout::Member m;
      m.kind = KindOf(src.type);
      m.field = static_cast<uint32_t>(i + 1);
      m.seq = t == 0 && src.name == "seq" && m.kind == Kind::kInt64 &&
              src.dims.empty();
      if (m.kind == Kind::kStruct) {
        const LcmStruct* child = registry.FindByName(src.type);
        if (child == nullptr) {
          throw std::runtime_error("LCM type " + s.full_name() + ": member '" +
                                   src.name + "' has unknown type " + src.type);
        }
        m.child = layout_of(*child);
      }
      for (const LcmDimension& dim : src.dims) {
        Layout::Dim d;
        if (dim.variable) {
          for (size_t j = 0; j < i; ++j) {
            if (s.members[j].name == dim.size) d.ref = static_cast<int>(j);
          }
        } else {
          d.fixed = std::stoll(dim.size);
        }
        m.dims.push_back(d);
      }
      l->members.push_back(std::move(m));
    }
  }
}

LcmProtobufEncoder::~LcmProtobufEncoder() = default;

bool LcmProtobufEncoder::Encode(const uint8_t* data, size_t size) {
  size_ = 0;
  has_seq_ = false;
  seq_ = 0;
  if (size < 8) return false;
  uint64_t hash = 0;
  for (size_t k = 0; k < 8; ++k) hash = (hash << 8) | data[k];
  if (static_cast<int64_t>(hash) != fingerprint_) return false;
  Run run(data + 8, size - 8, &buf_, &size_);
  if (!run.Struct(*layouts_[0], 0) || run.left() != 0) {
    size_ = 0;
    return false;
  }
  has_seq_ = run.has_seq;
  seq_ = run.seq;
  return true;
}

}  // namespace mrsim
