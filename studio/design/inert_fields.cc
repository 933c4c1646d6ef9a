#include "studio/design/inert_fields.h"

#include <algorithm>

namespace mrsim::studio {

std::vector<FieldRef> WithoutInert(std::vector<FieldRef> fields,
                                   const std::vector<std::string>& inert) {
  fields.erase(std::remove_if(fields.begin(), fields.end(),
                              [&](const FieldRef& f) {
                                for (const std::string& name : inert) {
                                  if (name == f.info().xml) {
                                    return true;
                                  }
                                }
                                return false;
                              }),
               fields.end());
  return fields;
}

std::vector<FieldRef> WithoutUnused(std::vector<FieldRef> fields) {
  auto is_true = [&](const std::string& xml) {
    for (const FieldRef& f : fields) {
      if (xml == f.info().xml) return f.GetText() == "true";
    }
    return false;
  };
  std::vector<FieldRef> kept;
  for (const FieldRef& f : fields) {
    const char* when = f.info().shown_when;
    if (when != nullptr) {
      const bool negated = when[0] == '!';
      if (is_true(negated ? when + 1 : when) == negated) continue;
    }
    kept.push_back(f);
  }
  return kept;
}

}  // namespace mrsim::studio
