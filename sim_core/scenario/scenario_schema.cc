#include "sim_core/scenario/scenario_schema.h"

#include <fmt/format.h>

#include <cctype>
#include <charconv>
#include <cmath>
#include <map>
#include <sstream>
#include <type_traits>

#include "common/trim.h"
#include "sim_core/scenario/scenario_schema_inl.h"
#include "sim_core/scenario/xml_writer.h"

namespace mrsim {
namespace {

// "A or B", "A, B, C or D".
std::string OrList(const std::vector<std::string>& names) {
  std::string r;
  for (size_t i = 0; i < names.size(); ++i) {
    if (i > 0) r += i + 1 == names.size() ? " or " : ", ";
    r += names[i];
  }
  return r;
}

template <typename E>
constexpr bool kIsChoice =
    std::is_same_v<E, Axis> || std::is_same_v<E, JointType> ||
    std::is_same_v<E, PrimitiveShape> || std::is_same_v<E, FluidKind> ||
    std::is_same_v<E, ClockMode> || std::is_same_v<E, ControllerKind>;

// A value beyond the field's physical bound (FieldLimits::magnitude).
std::string MagnitudeMessage(const FieldLimits& l, double v) {
  if (std::abs(v) <= l.magnitude) return "";
  return fmt::format("expected a value within -{0}..{0}, got {1}", l.magnitude,
                     v);
}

std::string NumberLimitMessage(const FieldLimits& l, double v) {
  const bool has_min = std::isfinite(l.min), has_max = std::isfinite(l.max);
  const bool ok = (!has_min || (l.min_exclusive ? v > l.min : v >= l.min)) &&
                  (!has_max || v <= l.max);
  if (ok) return MagnitudeMessage(l, v);
  if (has_min && has_max) {
    return fmt::format("expected {}..{}{}, got {}", l.min, l.max,
                       *l.meaning ? fmt::format(" ({})", l.meaning) : "", v);
  }
  if (has_min && l.min == 0) {
    return l.min_exclusive ? fmt::format("expected a positive value, got {}", v)
                           : fmt::format("expected a value >= 0, got {}", v);
  }
  if (has_min) {
    return fmt::format("expected {} {}, got {}",
                       l.min_exclusive ? "a value above" : "at least", l.min,
                       v);
  }
  return fmt::format("expected at most {}, got {}", l.max, v);
}

std::string VectorLimitMessage(const FieldLimits& l, const Eigen::Vector3d& v) {
  const std::string got = fmt::format("({}, {}, {})", v.x(), v.y(), v.z());
  for (int i = 0; i < 3; ++i) {
    if (MagnitudeMessage(l, v[i]).empty()) continue;
    return fmt::format("expected x, y, z within -{0}..{0}, got {1}",
                       l.magnitude, got);
  }
  if (l.nonzero && !(v.norm() > 0)) return "expected a non-zero vector";
  for (int i = 0; i < 3; ++i) {
    if (NumberLimitMessage(l, v[i]).empty()) continue;
    if (std::isfinite(l.min) && l.min == 0 && !std::isfinite(l.max)) {
      return l.min_exclusive ? "expected positive x, y, z, got " + got
                             : "expected x, y, z >= 0, got " + got;
    }
    return fmt::format("expected x, y, z in {}..{}, got {}", l.min, l.max, got);
  }
  return "";
}

// Message for a value outside the limits, "" when within.
template <typename T>
std::string LimitMessage(const FieldInfo& info, const T& v) {
  const FieldLimits& l = info.limits;
  if constexpr (std::is_same_v<T, std::string>) {
    if (l.nonempty && v.empty()) {
      return fmt::format("expected a non-empty {}", info.xml);
    }
    return l.max_bytes > 0 && v.size() > l.max_bytes
               ? fmt::format("expected at most {} bytes, got {}", l.max_bytes,
                             v.size())
               : "";
  } else if constexpr (std::is_same_v<T, double> || std::is_same_v<T, int>) {
    return NumberLimitMessage(l, v);
  } else if constexpr (std::is_same_v<T, Eigen::Vector3d>) {
    return VectorLimitMessage(l, v);
  } else if constexpr (std::is_same_v<T, Eigen::Quaterniond>) {
    for (int i = 0; i < 4; ++i) {
      if (MagnitudeMessage(l, v.coeffs()[i]).empty()) continue;
      return fmt::format(
          "expected x, y, z, w within -{0}..{0}, got ({1}, {2}, {3}, {4})",
          l.magnitude, v.x(), v.y(), v.z(), v.w());
    }
    return l.nonzero && !(v.coeffs().norm() > 0)
               ? "expected a rotation quaternion, got all zeros"
               : "";
  } else {
    return "";
  }
}

std::vector<double> ParseNumbers(const std::string& text, size_t n,
                                 const char* what) {
  std::string spaced = text;
  for (char& c : spaced) {
    if (c == ',' || c == '(' || c == ')') c = ' ';
  }
  std::istringstream in(spaced);
  std::vector<double> values;
  std::string word;
  while (in >> word) {
    try {
      values.push_back(ParseNumber(word));
    } catch (const FieldError&) {
      values.clear();
      break;
    }
  }
  if (values.size() != n) {
    throw FieldError(
        fmt::format("expected {} numbers {}, got '{}'", n, what, text));
  }
  return values;
}

template <typename T>
T ParseValue(const std::string& text) {
  if constexpr (std::is_same_v<T, std::string>) {
    return text;
  } else if constexpr (std::is_same_v<T, double>) {
    return ParseNumber(text);
  } else if constexpr (std::is_same_v<T, int>) {
    return ParseInteger(text);
  } else if constexpr (std::is_same_v<T, bool>) {
    return ParseBool(text);
  } else if constexpr (std::is_same_v<T, Eigen::Vector3d>) {
    const auto v = ParseNumbers(text, 3, "x y z");
    return Eigen::Vector3d(v[0], v[1], v[2]);
  } else if constexpr (std::is_same_v<T, Eigen::Quaterniond>) {
    const auto v = ParseNumbers(text, 4, "x y z w");
    return Eigen::Quaterniond(v[3], v[0], v[1], v[2]);
  } else {
    static_assert(kIsChoice<T>);
    const auto& names = schema::ChoiceNames(static_cast<const T*>(nullptr));
    const std::string t = Trim(text);
    for (size_t i = 0; i < names.size(); ++i) {
      if (names[i] == t) return static_cast<T>(i);
    }
    throw FieldError("expected " + OrList(names) + ", got '" + text + "'");
  }
}

template <typename T>
std::string FormatValue(const T& v) {
  if constexpr (std::is_same_v<T, std::string>) {
    return v;
  } else if constexpr (std::is_same_v<T, double>) {
    return FormatNumber(v);
  } else if constexpr (std::is_same_v<T, int>) {
    return std::to_string(v);
  } else if constexpr (std::is_same_v<T, bool>) {
    return v ? "true" : "false";
  } else if constexpr (std::is_same_v<T, Eigen::Vector3d>) {
    return FormatNumber(v.x()) + " " + FormatNumber(v.y()) + " " +
           FormatNumber(v.z());
  } else if constexpr (std::is_same_v<T, Eigen::Quaterniond>) {
    return FormatNumber(v.x()) + " " + FormatNumber(v.y()) + " " +
           FormatNumber(v.z()) + " " + FormatNumber(v.w());
  } else {
    static_assert(kIsChoice<T>);
    return schema::ChoiceNames(static_cast<const T*>(nullptr))
        .at(static_cast<size_t>(v));
  }
}

template <typename T>
FieldType TypeOf() {
  if constexpr (std::is_same_v<T, std::string>) return FieldType::kText;
  if constexpr (std::is_same_v<T, double>) return FieldType::kNumber;
  if constexpr (std::is_same_v<T, int>) return FieldType::kInteger;
  if constexpr (std::is_same_v<T, bool>) return FieldType::kBool;
  if constexpr (std::is_same_v<T, Eigen::Vector3d>) return FieldType::kVector;
  if constexpr (std::is_same_v<T, Eigen::Quaterniond>) {
    return FieldType::kQuaternion;
  }
  return FieldType::kChoice;
}

// Collects the fields of one part (not of its children).
struct FieldCollector {
  std::vector<FieldRef> fields;
  template <typename T>
  void Field(const FieldInfo& info, T& value) {
    fields.emplace_back(info, &value);
  }
  template <typename P>
  void Child(const ChildInfo&, P&) {}
  template <typename P>
  void Optional(const ChildInfo&, std::optional<P>&) {}
  template <typename P, size_t N>
  void Array(const ChildInfo&, std::array<P, N>&) {}
  template <typename P>
  void List(const ChildInfo&, std::vector<P>&) {}
  void Unsupported(const ChildInfo&) {}
};

struct ChildCollector {
  std::vector<ChildSpec> children;
  template <typename T>
  void Field(const FieldInfo&, T&) {}
  template <typename P>
  void Child(const ChildInfo& info, P&) {
    children.push_back({info, ChildCount::kOne, schema::KindOf<P>::kValue});
  }
  template <typename P>
  void Optional(const ChildInfo& info, std::optional<P>&) {
    children.push_back(
        {info, ChildCount::kOptional, schema::KindOf<P>::kValue});
  }
  template <typename P, size_t N>
  void Array(const ChildInfo& info, std::array<P, N>&) {
    children.push_back({info, ChildCount::kArray, schema::KindOf<P>::kValue});
  }
  template <typename P>
  void List(const ChildInfo& info, std::vector<P>&) {
    children.push_back({info,
                        *info.item ? ChildCount::kList : ChildCount::kRepeated,
                        schema::KindOf<P>::kValue});
  }
  void Unsupported(const ChildInfo&) {}
};

template <typename P>
std::vector<FieldRef> Collect(P& part) {
  FieldCollector c;
  schema::Describe(c, part);
  return c.fields;
}

template <typename P>
std::pair<std::vector<FieldSpec>, std::vector<ChildSpec>> Specs() {
  P part;
  std::vector<FieldSpec> fields;
  for (const FieldRef& f : Collect(part)) {
    fields.push_back({f.info(), f.type(), f.GetText(), f.choices()});
  }
  ChildCollector children;
  schema::Describe(children, part);
  return {fields, children.children};
}

const std::pair<std::vector<FieldSpec>, std::vector<ChildSpec>>& SpecsOf(
    PartKind kind) {
  static const auto table = [] {
    std::map<PartKind,
             std::pair<std::vector<FieldSpec>, std::vector<ChildSpec>>>
        t;
#define MRSIM_PART_KIND_SPECS(Kind, Name, Type) \
  t[PartKind::Kind] = Specs<Type>();
    MRSIM_PART_KINDS(MRSIM_PART_KIND_SPECS)
#undef MRSIM_PART_KIND_SPECS
    return t;
  }();
  return table.at(kind);
}

}  // namespace

const char* ToString(FieldType type) {
  switch (type) {
    case FieldType::kText:
      return "text";
    case FieldType::kNumber:
      return "number";
    case FieldType::kInteger:
      return "integer";
    case FieldType::kBool:
      return "bool";
    case FieldType::kVector:
      return "vector";
    case FieldType::kQuaternion:
      return "quaternion";
    case FieldType::kChoice:
      return "choice";
  }
  return "?";
}

const std::vector<PartKind>& AllPartKinds() {
  static const std::vector<PartKind> kinds{
#define MRSIM_PART_KIND_ITEM(Kind, Name, Type) PartKind::Kind,
      MRSIM_PART_KINDS(MRSIM_PART_KIND_ITEM)
#undef MRSIM_PART_KIND_ITEM
  };
  return kinds;
}

const char* ToString(PartKind kind) {
  switch (kind) {
#define MRSIM_PART_KIND_NAME(Kind, Name, Type) \
  case PartKind::Kind:                         \
    return Name;
    MRSIM_PART_KINDS(MRSIM_PART_KIND_NAME)
#undef MRSIM_PART_KIND_NAME
  }
  return "?";
}

double ParseNumber(const std::string& raw) {
  std::string text = Trim(raw);
  if (!text.empty() && text[0] == '+') text.erase(0, 1);
  double value = 0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end ||
      !std::isfinite(value)) {
    throw FieldError("expected a number, got '" + raw + "'");
  }
  return value;
}

int ParseInteger(const std::string& raw) {
  std::string text = Trim(raw);
  if (!text.empty() && text[0] == '+') text.erase(0, 1);
  int value = 0;
  const char* end = text.data() + text.size();
  auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (text.empty() || ec != std::errc() || ptr != end) {
    throw FieldError("expected an integer, got '" + raw + "'");
  }
  return value;
}

bool ParseBool(const std::string& raw) {
  const std::string text = Trim(raw);
  if (text == "true" || text == "1") return true;
  if (text == "false" || text == "0") return false;
  throw FieldError("expected true or false, got '" + raw + "'");
}

std::string FormatNumber(double value) { return FormatShortest(value); }

std::string ListLimitMessage(const ChildInfo& info) {
  const std::string why =
      *info.max_items_why ? std::string(": ") + info.max_items_why : "";
  if (*info.item) {
    return fmt::format("more than {} <{}> in <{}> (at most {}{})",
                       info.max_items, info.item, info.xml, info.max_items,
                       why);
  }
  return fmt::format("more than {} <{}> (at most {}{})", info.max_items,
                     info.xml, info.max_items, why);
}

FieldType FieldRef::type() const {
  return std::visit(
      [](auto* p) { return TypeOf<std::remove_pointer_t<decltype(p)>>(); },
      value_);
}

std::vector<std::string> FieldRef::choices() const {
  return std::visit(
      [](auto* p) -> std::vector<std::string> {
        using T = std::remove_pointer_t<decltype(p)>;
        if constexpr (kIsChoice<T>) {
          return schema::ChoiceNames(static_cast<const T*>(nullptr));
        } else {
          return {};
        }
      },
      value_);
}

std::string FieldRef::GetText() const {
  return std::visit([](auto* p) { return FormatValue(*p); }, value_);
}

void FieldRef::SetText(const std::string& text) const {
  std::visit(
      [&](auto* p) {
        using T = std::remove_pointer_t<decltype(p)>;
        T value = ParseValue<T>(text);
        const std::string problem = LimitMessage(*info_, value);
        if (!problem.empty()) throw FieldError(problem);
        *p = value;
      },
      value_);
}

void FieldRef::SetTextUnchecked(const std::string& text) const {
  std::visit(
      [&](auto* p) {
        using T = std::remove_pointer_t<decltype(p)>;
        *p = ParseValue<T>(text);
      },
      value_);
}

std::string FieldRef::Check() const {
  return std::visit([&](auto* p) { return LimitMessage(*info_, *p); }, value_);
}

std::vector<FieldRef> FieldsOf(Scenario& part) { return Collect(part); }
std::vector<FieldRef> FieldsOf(Robot& part) { return Collect(part); }
std::vector<FieldRef> FieldsOf(Module& part) { return Collect(part); }
std::vector<FieldRef> FieldsOf(Frame& part) { return Collect(part); }
std::vector<FieldRef> FieldsOf(Joint& part) { return Collect(part); }
std::vector<FieldRef> FieldsOf(SensorModule& part) { return Collect(part); }
std::vector<FieldRef> FieldsOf(ForceSensor& part) { return Collect(part); }
std::vector<FieldRef> FieldsOf(DistanceSensor& part) { return Collect(part); }
std::vector<FieldRef> FieldsOf(Imu& part) { return Collect(part); }
std::vector<FieldRef> FieldsOf(Camera& part) { return Collect(part); }
std::vector<FieldRef> FieldsOf(Scene& part) { return Collect(part); }
std::vector<FieldRef> FieldsOf(SceneObject& part) { return Collect(part); }
std::vector<FieldRef> FieldsOf(ContactFriction& part) { return Collect(part); }
std::vector<FieldRef> FieldsOf(FluidRegion& part) { return Collect(part); }
std::vector<FieldRef> FieldsOf(SimulationSettings& part) {
  return Collect(part);
}
std::vector<FieldRef> FieldsOf(RunSettings& part) { return Collect(part); }
std::vector<FieldRef> FieldsOf(OptimizationSettings& part) {
  return Collect(part);
}

const std::vector<FieldSpec>& FieldSpecsOf(PartKind kind) {
  return SpecsOf(kind).first;
}
const std::vector<ChildSpec>& ChildSpecsOf(PartKind kind) {
  return SpecsOf(kind).second;
}

}  // namespace mrsim
