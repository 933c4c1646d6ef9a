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

}  // namespace mrsim::studio
