#include "common/xml_error_text.h"

#include <tinyxml2.h>

namespace mrsim {

std::string XmlErrorText(const tinyxml2::XMLDocument& doc) {
  switch (doc.ErrorID()) {
    case tinyxml2::XML_ERROR_FILE_NOT_FOUND:
      return "no such file";
    case tinyxml2::XML_ERROR_FILE_COULD_NOT_BE_OPENED:
      return "cannot open the file";
    case tinyxml2::XML_ERROR_FILE_READ_ERROR:
      return "cannot read the file (is it a folder?)";
    case tinyxml2::XML_ERROR_MISMATCHED_ELEMENT:
      return "an element is closed by another name, or not closed";
    case tinyxml2::XML_ERROR_PARSING_ELEMENT:
      return "an element is cut short or not closed";
    case tinyxml2::XML_ERROR_PARSING_ATTRIBUTE:
      return "a malformed or repeated attribute";
    case tinyxml2::XML_ERROR_PARSING_TEXT:
      return "text that is not XML (a stray '<' or '&'?)";
    case tinyxml2::XML_ERROR_EMPTY_DOCUMENT:
      return "the file is empty";
    default:
      return doc.ErrorStr() ? doc.ErrorStr() : doc.ErrorName();
  }
}

}  // namespace mrsim
