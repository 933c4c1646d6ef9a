// Where the studio gets the scenario schema (FieldRef, FieldsOf) and the
// one validator from: sim_core, so the inspector names no field itself.
#pragma once

#include "sim_core/scenario/scenario_schema.h"
#include "sim_core/scenario/scenario_validate.h"
