// Quotes a word for a POSIX shell, so a printed command line (mrsim launch
// --dry-run) can be pasted back as it is.
#pragma once

#include <string>

namespace mrsim {

// The word itself when it holds only characters no shell treats specially;
// otherwise in single quotes (a ' inside becomes '\'').
std::string ShellQuote(const std::string& word);

}  // namespace mrsim
