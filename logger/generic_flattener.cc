#include "logger/generic_flattener.h"

#include <cstring>
#include <map>
#include <stdexcept>

#include "logger/csv_format.h"

namespace mrsim {

namespace {

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

// Bytes of one element; strings and structs take at least this many.
size_t WireSize(Kind k) {
  switch (k) {
    case Kind::kInt8:
    case Kind::kByte:
    case Kind::kBool:
      return 1;
    case Kind::kInt16:
      return 2;
    case Kind::kInt32:
    case Kind::kFloat:
    case Kind::kString:
      return 4;
    case Kind::kInt64:
    case Kind::kDouble:
      return 8;
    case Kind::kStruct:
      return 1;
  }
  return 1;
}

bool IsInteger(Kind k) {
  return k == Kind::kInt8 || k == Kind::kInt16 || k == Kind::kInt32 ||
         k == Kind::kInt64 || k == Kind::kByte || k == Kind::kBool;
}

std::string Join(const std::string& prefix, const std::string& name) {
  return prefix.empty() ? name : prefix + "." + name;
}

uint64_t BigEndian(const uint8_t* b, size_t n) {
  uint64_t v = 0;
  for (size_t k = 0; k < n; ++k) v = (v << 8) | b[k];
  return v;
}

}  // namespace

struct GenericFlattener::Layout {
  struct Dim {
    int64_t fixed = -1;  // constant size, or -1
    int ref = -1;        // index of the member holding the size
  };
  struct Member {
    std::string name;
    Kind kind;
    const Layout* child = nullptr;
    std::vector<Dim> dims;
    bool fixed_xyz = false;  // double/float[3]: .x .y .z
  };
  std::vector<Member> members;
  bool pose = false;  // pose_t: .x .y .z .qw .qx .qy .qz
  // Encoded bytes when every member has a fixed size (no strings, no
  // variable arrays), else -1: validation skips such structs in one step.
  int64_t fixed_size = -1;
};

namespace {

using Layout = GenericFlattener::Layout;

// Walks one encoded message with a compiled layout. `values`, `names` and
// `shape` are optional outputs (validation passes none).
class Walker {
 public:
  Walker(const uint8_t* data, size_t size, std::string* values,
         std::vector<std::string>* names, std::vector<int64_t>* shape)
      : p_(data), left_(size), values_(values), names_(names), shape_(shape) {}

  size_t left() const { return left_; }
  bool has_seq() const { return has_seq_; }
  const std::string& sender() const { return sender_; }
  int64_t seq() const { return seq_; }

  bool Struct(const Layout& s, const std::string& prefix, bool top) {
    const size_t base = ints_.size();
    ints_.resize(base + s.members.size(), 0);
    bool ok = true;
    for (size_t mi = 0; ok && mi < s.members.size(); ++mi) {
      ok = Member(s, mi, prefix, top, base);
    }
    ints_.resize(base);
    return ok;
  }

 private:
  bool Member(const Layout& s, size_t mi, const std::string& prefix, bool top,
              size_t base) {
    const Layout::Member& m = s.members[mi];
    if (m.dims.empty()) {
      const bool utime = top && m.name == "utime" && m.kind == Kind::kInt64;
      std::string name;
      if (names_ != nullptr) name = utime ? "time" : Join(prefix, m.name);
      if (m.kind == Kind::kStruct) {
        if (values_ == nullptr && names_ == nullptr &&
            m.child->fixed_size >= 0) {
          const uint8_t* unused = nullptr;
          return Take(static_cast<size_t>(m.child->fixed_size), &unused);
        }
        return Struct(*m.child, name, false);
      }
      int64_t iv = 0;
      capture_sender_ = top && m.kind == Kind::kString && m.name == "sender";
      if (!Scalar(m.kind, name, &iv, utime)) return false;
      ints_[base + mi] = iv;
      if (top && m.kind == Kind::kInt64 && m.name == "seq") {
        has_seq_ = true;
        seq_ = iv;
      }
      return true;
    }
    dims_.clear();
    int64_t count = 1;
    for (const Layout::Dim& d : m.dims) {
      const int64_t n = d.ref >= 0 ? ints_[base + d.ref] : d.fixed;
      if (n < 0 || n > kMaxElements) return false;
      dims_.push_back(n);
      count *= n;
      if (count > kMaxElements) return false;
    }
    if (shape_ != nullptr)
      shape_->insert(shape_->end(), dims_.begin(), dims_.end());
    const size_t elem = WireSize(m.kind);
    if (static_cast<uint64_t>(count) * elem > left_) return false;
    // Validation skips fixed-size elements in one step: a 50-module state
    // is then a few dozen steps, not one per number.
    if (values_ == nullptr && names_ == nullptr && m.kind != Kind::kString) {
      const int64_t bytes =
          m.kind == Kind::kStruct ? m.child->fixed_size : WireSize(m.kind);
      if (bytes >= 0) {
        if (static_cast<uint64_t>(count) * bytes > left_) return false;
        p_ += count * bytes;
        left_ -= count * bytes;
        return true;
      }
    }
    const std::vector<int64_t> dims = dims_;
    for (int64_t i = 0; i < count; ++i) {
      std::string name;
      if (names_ != nullptr) name = ElementName(prefix, m, dims, i, s.pose);
      if (m.kind == Kind::kStruct) {
        if (!Struct(*m.child, name, false)) return false;
      } else {
        int64_t unused = 0;
        if (!Scalar(m.kind, name, &unused, false)) return false;
      }
    }
    return true;
  }

  static std::string ElementName(const std::string& prefix,
                                 const Layout::Member& m,
                                 const std::vector<int64_t>& dims, int64_t i,
                                 bool pose) {
    static const char* const kXyz[] = {"x", "y", "z"};
    static const char* const kQuat[] = {"qw", "qx", "qy", "qz"};
    if (pose && m.name == "position" && i < 3) return Join(prefix, kXyz[i]);
    if (pose && m.name == "orientation" && i < 4) {
      return Join(prefix, kQuat[i]);
    }
    if (m.fixed_xyz) return Join(prefix, m.name) + "." + kXyz[i];
    // Row-major index, one number per dimension: name3 or name2_1.
    std::vector<int64_t> idx(dims.size());
    int64_t rest = i;
    for (size_t d = dims.size(); d-- > 0;) {
      idx[d] = rest % dims[d];
      rest /= dims[d];
    }
    std::string name = Join(prefix, m.name);
    for (size_t d = 0; d < idx.size(); ++d) {
      if (d > 0) name += "_";
      name += std::to_string(idx[d]);
    }
    return name;
  }

  bool Take(size_t n, const uint8_t** out) {
    if (n > left_) return false;
    *out = p_;
    p_ += n;
    left_ -= n;
    return true;
  }

  void Cell(const std::string& name) {
    if (names_ != nullptr) names_->push_back(name);
    if (values_ != nullptr && !first_cell_) values_->push_back(',');
    first_cell_ = false;
  }

  bool Scalar(Kind kind, const std::string& name, int64_t* iv, bool utime) {
    const uint8_t* b = nullptr;
    if (kind == Kind::kString) {
      if (!Take(4, &b)) return false;
      const int64_t len = static_cast<int32_t>(BigEndian(b, 4));
      if (len < 1 || !Take(static_cast<size_t>(len), &b)) return false;
      if (b[len - 1] != 0) return false;
      if (capture_sender_) {
        const char* text = reinterpret_cast<const char*>(b);
        sender_.assign(text, std::strlen(text));
        capture_sender_ = false;
      }
      Cell(name);
      if (values_ != nullptr) {
        const char* text = reinterpret_cast<const char*>(b);
        AppendCsvText(std::string_view(text, std::strlen(text)), values_);
      }
      return true;
    }
    const size_t n = WireSize(kind);
    if (!Take(n, &b)) return false;
    const uint64_t raw = BigEndian(b, n);
    Cell(name);
    switch (kind) {
      case Kind::kDouble: {
        double d;
        std::memcpy(&d, &raw, 8);
        if (values_ != nullptr) AppendDouble(d, values_);
        return true;
      }
      case Kind::kFloat: {
        const uint32_t r32 = static_cast<uint32_t>(raw);
        float f;
        std::memcpy(&f, &r32, 4);
        if (values_ != nullptr) AppendFloat(f, values_);
        return true;
      }
      case Kind::kByte:
        *iv = static_cast<int64_t>(raw);
        break;
      case Kind::kInt8:
      case Kind::kBool:
        *iv = static_cast<int8_t>(raw);
        break;
      case Kind::kInt16:
        *iv = static_cast<int16_t>(raw);
        break;
      case Kind::kInt32:
        *iv = static_cast<int32_t>(raw);
        break;
      default:
        *iv = static_cast<int64_t>(raw);
        break;
    }
    if (values_ != nullptr) {
      if (utime) {
        AppendDouble(SecondsFromUtime(*iv), values_);
      } else {
        AppendInt(*iv, values_);
      }
    }
    return true;
  }

  const uint8_t* p_;
  size_t left_;
  std::string* values_;
  std::vector<std::string>* names_;
  std::vector<int64_t>* shape_;
  std::vector<int64_t> ints_;  // integer members of the structs being read
  std::vector<int64_t> dims_;
  bool first_cell_ = true;
  bool has_seq_ = false;
  bool capture_sender_ = false;
  std::string sender_;
  int64_t seq_ = 0;
};

// Compiles `s` and the structs it uses into `out` ([0] is `s`).
class Compiler {
 public:
  Compiler(const LcmTypeRegistry& registry,
           std::vector<std::unique_ptr<Layout>>* out)
      : registry_(registry), out_(out) {}

  Layout* Compile(const LcmStruct& s) {
    auto it = done_.find(s.full_name());
    if (it != done_.end()) return it->second;
    out_->push_back(std::make_unique<Layout>());
    Layout* layout = out_->back().get();
    done_[s.full_name()] = layout;
    layout->pose = s.name == "pose_t" && s.members.size() == 2 &&
                   s.members[0].name == "position" &&
                   s.members[1].name == "orientation";
    for (const LcmMember& m : s.members) {
      Layout::Member cm;
      cm.name = m.name;
      cm.kind = KindOf(m.type);
      if (cm.kind == Kind::kStruct) {
        const LcmStruct* child = registry_.FindByName(m.type);
        if (child == nullptr) {
          throw std::runtime_error("LCM type " + s.full_name() + ": member '" +
                                   m.name + "' has unknown type " + m.type);
        }
        cm.child = Compile(*child);
      }
      for (const LcmDimension& d : m.dims) {
        Layout::Dim cd;
        if (d.variable) {
          for (size_t k = 0; k < s.members.size(); ++k) {
            if (s.members[k].name == d.size) cd.ref = static_cast<int>(k);
          }
          if (cd.ref < 0 || !IsInteger(KindOf(s.members[cd.ref].type))) {
            throw std::runtime_error("LCM type " + s.full_name() +
                                     ": array size '" + d.size +
                                     "' is not an integer member");
          }
        } else {
          cd.fixed = std::strtoll(d.size.c_str(), nullptr, 10);
        }
        cm.dims.push_back(cd);
      }
      cm.fixed_xyz = cm.dims.size() == 1 && cm.dims[0].fixed == 3 &&
                     (cm.kind == Kind::kDouble || cm.kind == Kind::kFloat);
      layout->members.push_back(std::move(cm));
    }
    layout->fixed_size = FixedSize(*layout);
    return layout;
  }

 private:
  // A struct still being compiled (a cycle) counts as variable.
  static int64_t FixedSize(const Layout& layout) {
    int64_t total = 0;
    for (const Layout::Member& m : layout.members) {
      if (m.kind == Kind::kString) return -1;
      int64_t bytes = m.kind == Kind::kStruct ? m.child->fixed_size
                                              : int64_t(WireSize(m.kind));
      if (bytes < 0) return -1;
      for (const Layout::Dim& d : m.dims) {
        if (d.fixed < 0 || d.fixed > kMaxElements) return -1;
        bytes *= d.fixed;
        if (bytes > kMaxElements * 8) return -1;
      }
      total += bytes;
      if (total > kMaxElements * 8) return -1;
    }
    return total;
  }

  const LcmTypeRegistry& registry_;
  std::vector<std::unique_ptr<Layout>>* out_;
  std::map<std::string, Layout*> done_;
};

int64_t ReadFingerprint(const uint8_t* data) {
  return static_cast<int64_t>(BigEndian(data, 8));
}

}  // namespace

GenericFlattener::GenericFlattener(const LcmTypeRegistry& registry,
                                   const LcmStruct& type)
    : type_name_(type.full_name()), fingerprint_(registry.Fingerprint(type)) {
  Compiler(registry, &layouts_).Compile(type);
}

GenericFlattener::~GenericFlattener() = default;

bool GenericFlattener::IsWellFormed(const uint8_t* data, size_t size) const {
  if (size < 8 || ReadFingerprint(data) != fingerprint_) return false;
  Walker w(data + 8, size - 8, nullptr, nullptr, nullptr);
  return w.Struct(*layouts_[0], "", true) && w.left() == 0;
}

bool GenericFlattener::Flatten(const uint8_t* data, size_t size, FlatRow* row) {
  if (size < 8 || ReadFingerprint(data) != fingerprint_) return false;
  row->values.clear();
  shape_.clear();
  Walker w(data + 8, size - 8, &row->values, nullptr, &shape_);
  if (!w.Struct(*layouts_[0], "", true) || w.left() != 0) return false;
  row->has_seq = w.has_seq();
  row->seq = w.seq();
  row->sender = w.sender();
  if (!have_shape_ || shape_ != last_shape_) {
    std::vector<std::string> names;
    Walker named(data + 8, size - 8, nullptr, &names, nullptr);
    named.Struct(*layouts_[0], "", true);
    SetColumns(std::move(names));
    last_shape_ = shape_;
    have_shape_ = true;
  }
  return true;
}

}  // namespace mrsim
