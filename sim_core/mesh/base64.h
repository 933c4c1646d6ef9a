// Base64 (RFC 4648, standard alphabet, '=' padding) for image bytes embedded
// in scenario files.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace mrsim {

// Encodes bytes without line breaks.
std::string Base64Encode(const std::vector<unsigned char>& bytes);

// Decodes; whitespace (line breaks) is skipped. Throws std::invalid_argument
// naming the offending position on any other character outside the
// alphabet or on wrong padding.
std::vector<unsigned char> Base64Decode(const std::string& text);

}  // namespace mrsim
