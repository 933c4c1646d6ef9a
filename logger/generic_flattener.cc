#include "logger/generic_flattener.h"

#include <cstring>

#include "logger/csv_format.h"

namespace mrsim {
namespace {

constexpr int64_t kMaxElements = int64_t{1} << 26;

std::string Join(const std::string& prefix, const std::string& name) {
  return prefix.empty() ? name : prefix + "." + name;
}

bool IsPose(const LcmStruct& s) {
  return s.name == "pose_t" && s.members.size() == 2 &&
         s.members[0].name == "position" && s.members[1].name == "orientation";
}

size_t MinSize(const std::string& type) {
  if (type == "int8_t" || type == "byte" || type == "boolean") return 1;
  if (type == "int16_t") return 2;
  if (type == "int32_t" || type == "float" || type == "string") return 4;
  if (type == "int64_t" || type == "double") return 8;
  return 1;  // a struct: at least one byte unless it is empty
}

// Reads one encoded message member by member. `values`, `names` and `shape`
// are optional outputs (a validation pass passes none).
class Walker {
 public:
  Walker(const LcmTypeRegistry& registry, const uint8_t* data, size_t size,
         std::string* values, std::vector<std::string>* names,
         std::vector<int64_t>* shape)
      : registry_(registry),
        p_(data),
        left_(size),
        values_(values),
        names_(names),
        shape_(shape) {}

  size_t left() const { return left_; }
  bool has_seq() const { return has_seq_; }
  int64_t seq() const { return seq_; }

  bool Struct(const LcmStruct& s, const std::string& prefix, bool top) {
    std::vector<std::pair<const std::string*, int64_t>> ints;
    const bool pose = IsPose(s);
    for (const LcmMember& m : s.members) {
      std::vector<int64_t> dims;
      int64_t count = 1;
      for (const LcmDimension& d : m.dims) {
        int64_t n = -1;
        if (d.variable) {
          for (const auto& [name, v] : ints) {
            if (*name == d.size) n = v;
          }
        } else {
          n = std::strtoll(d.size.c_str(), nullptr, 10);
        }
        if (n < 0 || n > kMaxElements) return false;
        dims.push_back(n);
        count *= n;
        if (count > kMaxElements) return false;
      }
      if (!m.dims.empty()) {
        if (shape_ != nullptr)
          shape_->insert(shape_->end(), dims.begin(), dims.end());
        if (static_cast<uint64_t>(count) * MinSize(m.type) > left_)
          return false;
      }
      const LcmStruct* child = nullptr;
      if (!IsLcmPrimitive(m.type)) {
        child = registry_.FindByName(m.type);
        if (child == nullptr) return false;
      }
      if (m.dims.empty()) {
        const std::string name =
            names_ == nullptr ? std::string()
            : (top && m.name == "utime" && m.type == "int64_t")
                ? std::string("time")
                : Join(prefix, m.name);
        if (child != nullptr) {
          if (!Struct(*child, name, false)) return false;
          continue;
        }
        int64_t iv = 0;
        if (!Scalar(m.type, name, &iv, top && m.name == "utime")) return false;
        if (m.type != "string" && m.type != "float" && m.type != "double") {
          ints.emplace_back(&m.name, iv);
        }
        if (top && m.name == "seq" && m.type == "int64_t") {
          has_seq_ = true;
          seq_ = iv;
        }
        continue;
      }
      for (int64_t i = 0; i < count; ++i) {
        std::string name;
        if (names_ != nullptr) name = ElementName(prefix, m, dims, i, pose);
        if (child != nullptr) {
          if (!Struct(*child, name, false)) return false;
        } else {
          int64_t unused = 0;
          if (!Scalar(m.type, name, &unused, false)) return false;
        }
      }
    }
    return true;
  }

 private:
  static std::string ElementName(const std::string& prefix, const LcmMember& m,
                                 const std::vector<int64_t>& dims, int64_t i,
                                 bool pose) {
    static const char* const kXyz[] = {"x", "y", "z"};
    static const char* const kQuat[] = {"qw", "qx", "qy", "qz"};
    if (pose && m.name == "position" && i < 3) return Join(prefix, kXyz[i]);
    if (pose && m.name == "orientation" && i < 4) {
      return Join(prefix, kQuat[i]);
    }
    if (dims.size() == 1 && !m.dims[0].variable && dims[0] == 3 &&
        (m.type == "double" || m.type == "float")) {
      return Join(prefix, m.name) + "." + kXyz[i];
    }
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

  static uint64_t BigEndian(const uint8_t* b, int n) {
    uint64_t v = 0;
    for (int k = 0; k < n; ++k) v = (v << 8) | b[k];
    return v;
  }

  void Cell(const std::string& name) {
    if (names_ != nullptr) names_->push_back(name);
    if (values_ != nullptr && !first_cell_) values_->push_back(',');
    first_cell_ = false;
  }

  bool Scalar(const std::string& type, const std::string& name, int64_t* iv,
              bool utime) {
    const uint8_t* b = nullptr;
    if (type == "string") {
      if (!Take(4, &b)) return false;
      const int64_t len = static_cast<int32_t>(BigEndian(b, 4));
      if (len < 1 || !Take(static_cast<size_t>(len), &b)) return false;
      if (b[len - 1] != 0) return false;
      Cell(name);
      if (values_ != nullptr) {
        AppendCsvText(
            std::string_view(reinterpret_cast<const char*>(b),
                             std::strlen(reinterpret_cast<const char*>(b))),
            values_);
      }
      return true;
    }
    const size_t n = MinSize(type);
    if (!Take(n, &b)) return false;
    const uint64_t raw = BigEndian(b, static_cast<int>(n));
    Cell(name);
    if (type == "double") {
      double d;
      std::memcpy(&d, &raw, 8);
      if (values_ != nullptr) AppendDouble(d, values_);
      return true;
    }
    if (type == "float") {
      const uint32_t r32 = static_cast<uint32_t>(raw);
      float f;
      std::memcpy(&f, &r32, 4);
      if (values_ != nullptr) AppendFloat(f, values_);
      return true;
    }
    if (type == "byte") {
      *iv = static_cast<int64_t>(raw);
    } else if (type == "int8_t" || type == "boolean") {
      *iv = static_cast<int8_t>(raw);
    } else if (type == "int16_t") {
      *iv = static_cast<int16_t>(raw);
    } else if (type == "int32_t") {
      *iv = static_cast<int32_t>(raw);
    } else {
      *iv = static_cast<int64_t>(raw);
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

  const LcmTypeRegistry& registry_;
  const uint8_t* p_;
  size_t left_;
  std::string* values_;
  std::vector<std::string>* names_;
  std::vector<int64_t>* shape_;
  bool first_cell_ = true;
  bool has_seq_ = false;
  int64_t seq_ = 0;
};

int64_t ReadFingerprint(const uint8_t* data) {
  uint64_t v = 0;
  for (int k = 0; k < 8; ++k) v = (v << 8) | data[k];
  return static_cast<int64_t>(v);
}

}  // namespace

GenericFlattener::GenericFlattener(const LcmTypeRegistry& registry,
                                   const LcmStruct& type)
    : registry_(registry),
      type_(type),
      fingerprint_(registry.Fingerprint(type)) {}

bool GenericFlattener::IsWellFormedBody(const LcmTypeRegistry& registry,
                                        const LcmStruct& type,
                                        const uint8_t* body, size_t size) {
  Walker w(registry, body, size, nullptr, nullptr, nullptr);
  return w.Struct(type, "", true) && w.left() == 0;
}

bool GenericFlattener::Flatten(const uint8_t* data, size_t size, FlatRow* row) {
  if (size < 8 || ReadFingerprint(data) != fingerprint_) return false;
  row->values.clear();
  std::vector<int64_t> shape;
  Walker w(registry_, data + 8, size - 8, &row->values, nullptr, &shape);
  if (!w.Struct(type_, "", true) || w.left() != 0) return false;
  row->has_seq = w.has_seq();
  row->seq = w.seq();
  if (!have_shape_ || shape != last_shape_) {
    std::vector<std::string> names;
    Walker named(registry_, data + 8, size - 8, nullptr, &names, nullptr);
    named.Struct(type_, "", true);
    SetColumns(std::move(names));
    last_shape_ = std::move(shape);
    have_shape_ = true;
  }
  return true;
}

}  // namespace mrsim
