// What tinyxml2 found wrong with a file, in words for the person who edited
// it ("an element is closed by another name, or not closed"), instead of
// its own "Error=XML_ERROR_MISMATCHED_ELEMENT ErrorID=14 (0xe) ...".
#pragma once

#include <string>

namespace tinyxml2 {
class XMLDocument;
}

namespace mrsim {

// The error of a document whose Parse or LoadFile failed.
std::string XmlErrorText(const tinyxml2::XMLDocument& doc);

}  // namespace mrsim
