# Writes OUT, a C++ file defining mrsim::LuaTemplates() from the .lua files
# in DIR (run at build time, so editing a template rebuilds it).
file(GLOB files ${DIR}/*.lua)
list(SORT files)
set(body "")
foreach(f ${files})
  get_filename_component(name ${f} NAME_WE)
  file(READ ${f} text)
  string(APPEND body "      {\"${name}\", R\"mrsimlua(${text})mrsimlua\"},\n")
endforeach()
file(WRITE ${OUT}.tmp
"// Generated from lua_controller/templates/*.lua by embed_templates.cmake.
#include \"lua_controller/lua_templates.h\"

namespace mrsim {

const std::vector<LuaTemplate>& LuaTemplates() {
  static const std::vector<LuaTemplate> templates = {
${body}  };
  return templates;
}

}  // namespace mrsim
")
file(COPY_FILE ${OUT}.tmp ${OUT} ONLY_IF_DIFFERENT)
