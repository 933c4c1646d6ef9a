#include "wire_sample.h"

#include <map>
#include <set>
#include <stdexcept>

namespace mrsim::testing {
namespace {

size_t PrimitiveSize(const std::string& type) {
  static const std::map<std::string, size_t> kSizes = {
      {"int8_t", 1},  {"byte", 1},  {"boolean", 1}, {"int16_t", 2},
      {"int32_t", 4}, {"float", 4}, {"int64_t", 8}, {"double", 8}};
  const auto it = kSizes.find(type);
  return it == kSizes.end() ? 0 : it->second;
}

class Builder {
 public:
  Builder(const LcmTypeRegistry& registry, int count, WireSample* out)
      : registry_(registry), count_(count), out_(out) {}

  void Struct(const LcmStruct& s, const std::string& prefix) {
    std::set<std::string> length_members;
    for (const LcmMember& m : s.members) {
      for (const LcmDimension& d : m.dims) {
        if (d.variable) length_members.insert(d.size);
      }
    }
    for (const LcmMember& m : s.members) {
      const std::string name = prefix + "." + m.name;
      if (length_members.count(m.name) > 0) {
        Length(name, PrimitiveSize(m.type), false, count_);
        continue;
      }
      int64_t n = 1;
      for (const LcmDimension& d : m.dims) {
        n *= d.variable ? count_ : std::stoll(d.size);
      }
      for (int64_t i = 0; i < n; ++i) Element(m.type, name);
    }
  }

 private:
  void Element(const std::string& type, const std::string& name) {
    if (type == "string") {
      Length(name, 4, true, 3);
      for (char c : {'a', 'b', '\0'}) out_->bytes.push_back(c);
    } else if (type == "boolean") {
      out_->bytes.push_back(1);
    } else if (const size_t size = PrimitiveSize(type); size > 0) {
      // Varied bytes, so a misplaced field would not go unnoticed.
      for (size_t k = 0; k < size; ++k) {
        out_->bytes.push_back(
            static_cast<uint8_t>(out_->bytes.size() * 37 + 11));
      }
    } else {
      const LcmStruct* child = registry_.FindByName(type);
      if (child == nullptr) throw std::runtime_error("unknown type " + type);
      Struct(*child, name);
    }
  }

  void Length(const std::string& name, size_t width, bool string,
              int64_t value) {
    out_->lengths.push_back({name, out_->bytes.size(), width, string});
    out_->bytes.resize(out_->bytes.size() + width);
    PutBigEndian(&out_->bytes, out_->bytes.size() - width, width, value);
  }

  const LcmTypeRegistry& registry_;
  int count_;
  WireSample* out_;
};

}  // namespace

void PutBigEndian(std::vector<uint8_t>* bytes, size_t offset, size_t width,
                  int64_t value) {
  const auto v = static_cast<uint64_t>(value);
  for (size_t k = 0; k < width; ++k) {
    (*bytes)[offset + k] = static_cast<uint8_t>(v >> (8 * (width - 1 - k)));
  }
}

WireSample BuildWireSample(const LcmTypeRegistry& registry,
                           const LcmStruct& type, int64_t fingerprint,
                           int count) {
  WireSample out;
  out.bytes.resize(8);
  PutBigEndian(&out.bytes, 0, 8, fingerprint);
  Builder(registry, count, &out).Struct(type, type.name);
  return out;
}

}  // namespace mrsim::testing
