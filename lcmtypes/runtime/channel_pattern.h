// LCM subscribes by regular expression (GLib's): a channel name used as a
// pattern must have its special characters escaped, or "A.B" also takes
// "AxB". One escaping for every subscriber built from names.
#pragma once

#include <string>

namespace mrsim {

// `name` as a pattern that matches exactly that name.
std::string LiteralChannelPattern(const std::string& name);

}  // namespace mrsim
