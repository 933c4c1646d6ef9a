// Where the studio gets the scenario schema (FieldRef, FieldsOf) and the
// validator from. Until the schema branch is merged this is the temporary
// adapter; afterwards sim_core/scenario_schema.h and scenario_validate.h.
#pragma once

#include "studio/schema_adapter.h"
