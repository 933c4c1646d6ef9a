#include "lcmtypes/runtime/channel_pattern.h"

#include <glib.h>

#include <memory>

namespace mrsim {

std::string LiteralChannelPattern(const std::string& name) {
  std::unique_ptr<gchar, decltype(&g_free)> escaped(
      g_regex_escape_string(name.c_str(), static_cast<gint>(name.size())),
      &g_free);
  return escaped.get();
}

}  // namespace mrsim
