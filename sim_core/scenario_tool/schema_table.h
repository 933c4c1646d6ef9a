// The schema as Markdown tables, one per part, for `mrsim-scenario schema`
// and docs/scenario.md: what the table in scenario_schema.h says, printed.
#pragma once

#include <string>

#include "sim_core/scenario/scenario_schema.h"

namespace mrsim {

// "> 0", ">= 0", "0..3 (bottom, left, top, right)", "non-zero", "" ...
std::string LimitsText(const FieldLimits& limits, FieldType type);

// Every part: its fields (XML name, type, unit, limits, default, required,
// help) and its children.
std::string SchemaMarkdown();

}  // namespace mrsim
