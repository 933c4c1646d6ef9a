#include "studio/design/inert_fields.h"

#include <algorithm>
#include <cstring>

namespace mrsim::studio {

std::vector<FieldRef> WithoutInert(std::vector<FieldRef> fields,
                                   std::initializer_list<const char*> inert) {
  fields.erase(std::remove_if(fields.begin(), fields.end(),
                              [&](const FieldRef& f) {
                                for (const char* name : inert) {
                                  if (std::strcmp(f.info().xml, name) == 0) {
                                    return true;
                                  }
                                }
                                return false;
                              }),
               fields.end());
  return fields;
}

}  // namespace mrsim::studio
