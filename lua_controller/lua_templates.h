// The example Lua controllers shipped in lua_controller/templates/, built
// into the program so the studio can offer them without looking for files.
#pragma once

#include <string>
#include <vector>

namespace mrsim {

struct LuaTemplate {
  std::string name;    // "sine", "serpenoid"
  std::string source;  // the script
};

const std::vector<LuaTemplate>& LuaTemplates();

}  // namespace mrsim
