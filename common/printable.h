// Text from the network or a file made safe for a terminal or a log: a
// forged run name or sender must not move the cursor, recolour or retitle
// the terminal of whoever reads mrsim's output.
#pragma once

#include <string>
#include <string_view>

namespace mrsim {

// `text` with every control byte (below 0x20 except tab, and 0x7f) written
// as \xNN and a backslash as \\, so the line shows what arrived and
// nothing else. Other bytes (UTF-8 included) pass unchanged.
std::string Printable(std::string_view text);

}  // namespace mrsim
