#include "sim_core/scenario/scene_object_name.h"

#include <cctype>

namespace mrsim {

bool IsGeneratedGuid(const std::string& guid) {
  if (guid.size() != 36) return false;
  for (size_t i = 0; i < guid.size(); ++i) {
    const bool dash = i == 8 || i == 13 || i == 18 || i == 23;
    if (dash != (guid[i] == '-')) return false;
    if (!dash && !std::isxdigit(static_cast<unsigned char>(guid[i]))) {
      return false;
    }
  }
  return true;
}

std::string SceneObjectGivenName(const SceneObject& object) {
  return IsGeneratedGuid(object.guid) ? std::string() : object.guid;
}

std::string SceneObjectLabel(const SceneObject& object, std::size_t index) {
  const std::string name = SceneObjectGivenName(object);
  return name.empty() ? "object " + std::to_string(index) : name;
}

}  // namespace mrsim
