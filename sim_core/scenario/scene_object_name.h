// What a person called a scene object, so messages and summaries name it
// as the user did ("ball") and not by its place in the file: the overlap
// check, `mrsim run`'s summary.
#pragma once

#include <cstddef>
#include <string>

#include "sim_core/scenario/scenario.h"

namespace mrsim {

// A generated GUID ("7b579252-58ce-4fb0-937f-57c24696363f", what the
// original MRSim gave every part) names nothing for a person.
bool IsGeneratedGuid(const std::string& guid);

// The object's guid, the name the studio and users give it; "" when it
// has none (empty, or a generated GUID): then callers say "object <i>".
std::string SceneObjectGivenName(const SceneObject& object);

// "ball", or "object 3" (its index in the file) when it has no name.
std::string SceneObjectLabel(const SceneObject& object, std::size_t index);

}  // namespace mrsim
