#include "sim_core/scenario_tool/schema_table.h"

#include <fmt/format.h>

#include <cmath>

namespace mrsim {

std::string LimitsText(const FieldLimits& l, FieldType type) {
  std::string text;
  auto add = [&](const std::string& s) {
    text += (text.empty() ? "" : ", ") + s;
  };
  const bool has_min = std::isfinite(l.min), has_max = std::isfinite(l.max);
  const std::string each = type == FieldType::kVector ? "each " : "";
  if (has_min && has_max) {
    add(fmt::format("{}{}..{}", each, l.min, l.max));
    if (*l.meaning) text += fmt::format(" ({})", l.meaning);
  } else if (has_min) {
    add(fmt::format("{}{} {}", each, l.min_exclusive ? ">" : ">=", l.min));
  } else if (has_max) {
    add(fmt::format("{}<= {}", each, l.max));
  }
  // Every number has a bound; the table names those tighter than the one
  // for all (docs/scenario.md, "Limits").
  if (l.magnitude < kMaxAnyValue && !(has_max && l.max <= l.magnitude)) {
    if (has_min && l.min >= -l.magnitude) {
      add(fmt::format("{}<= {}", each, l.magnitude));
    } else {
      add(fmt::format("{}within -{}..{}", each, l.magnitude, l.magnitude));
    }
  }
  if (l.nonzero) add("not all zero");
  if (l.nonempty) add("not empty");
  if (l.max_bytes > 0) add(fmt::format("at most {} bytes", l.max_bytes));
  return text;
}

namespace {

const char* CountText(ChildCount count) {
  switch (count) {
    case ChildCount::kOne:
      return "one";
    case ChildCount::kOptional:
      return "optional";
    case ChildCount::kArray:
      return "exactly 2";
    case ChildCount::kList:
      return "list";
    case ChildCount::kRepeated:
      return "repeated";
  }
  return "";
}

}  // namespace

std::string SchemaMarkdown() {
  std::string out;
  // Every part, in the enum's order (a new part kind is listed by itself).
  for (const PartKind kind : AllPartKinds()) {
    out += fmt::format("### {}\n\n", ToString(kind));
    const auto& fields = FieldSpecsOf(kind);
    if (!fields.empty()) {
      out +=
          "| element | member | type | unit | limits | default | what |\n"
          "|---|---|---|---|---|---|---|\n";
      for (const FieldSpec& f : fields) {
        std::string def = f.info.required ? "(required)" : f.default_text;
        if (def.empty()) def = "\"\"";
        std::string type = ToString(f.type);
        if (!f.choices.empty()) {
          type.clear();
          for (const std::string& c : f.choices) {
            type += (type.empty() ? "" : "\\|") + c;
          }
        }
        out += fmt::format("| `{}` | {} | {} | {} | {} | {} | {} |\n",
                           f.info.xml, f.info.member, type, f.info.unit,
                           LimitsText(f.info.limits, f.type), def, f.info.help);
      }
      out += "\n";
    }
    const auto& children = ChildSpecsOf(kind);
    if (!children.empty()) {
      out += "Children: ";
      for (size_t i = 0; i < children.size(); ++i) {
        const ChildSpec& c = children[i];
        out += i ? "; " : "";
        out += *c.info.item
                   ? fmt::format("`{}/{}` ({}", c.info.xml, c.info.item,
                                 CountText(c.count))
                   : fmt::format("`{}` ({}", c.info.xml, CountText(c.count));
        if (c.count == ChildCount::kList || c.count == ChildCount::kRepeated)
          out += fmt::format(", at most {}", c.info.max_items);
        if (c.info.required) out += ", required";
        out += ")";
      }
      out += ".\n\n";
    }
  }
  return out;
}

}  // namespace mrsim
