#include "sim_core/scenario/run_settings.h"

namespace mrsim {

const EnumTable<ControllerKind>& ControllerKinds() {
  static const EnumTable<ControllerKind> kKinds(
      "controller", {{ControllerKind::kGait, "gait"},
                     {ControllerKind::kLua, "lua"},
                     {ControllerKind::kExternal, "external"}});
  return kKinds;
}

bool ValidControllerName(const std::string& name) {
  if (name.empty() || name.size() > kMaxRunNameBytes || name[0] == '-' ||
      name[0] == '.') {
    return false;  // never taken for a flag
  }
  for (char c : name) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') ||
                    (c >= '0' && c <= '9') || c == '-' || c == '_' || c == '.';
    if (!ok) return false;
  }
  return true;
}

}  // namespace mrsim
