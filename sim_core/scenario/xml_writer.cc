#include "sim_core/scenario/xml_writer.h"

#include <fmt/format.h>
#include <tinyxml2.h>

namespace mrsim {

// XMLPrinter indents by four and closes empty elements with "/>"; the
// files mrsim reads and writes use two and " />" as XmlSerializer did.
class XmlWriter::Printer : public tinyxml2::XMLPrinter {
 public:
  void CloseElement(bool compact_mode = false) override {
    if (_elementJustOpened) Write(" ", 1);
    tinyxml2::XMLPrinter::CloseElement(compact_mode);
  }

 protected:
  void PrintSpace(int depth) override {
    for (int i = 0; i < depth; ++i) Write("  ", 2);
  }
};

XmlWriter::XmlWriter() : printer_(std::make_unique<Printer>()) {
  printer_->PushDeclaration("xml version=\"1.0\" encoding=\"utf-8\"");
}

XmlWriter::~XmlWriter() = default;

void XmlWriter::Open(const std::string& name) {
  // XMLPrinter keeps the name's pointer until the element closes.
  names_.push_back(name);
  printer_->OpenElement(names_.back().c_str());
}

void XmlWriter::Attribute(const std::string& name, const std::string& value) {
  printer_->PushAttribute(name.c_str(), value.c_str());
}

void XmlWriter::Attribute(const std::string& name, double value) {
  Attribute(name, FormatShortest(value));
}

void XmlWriter::Close() {
  printer_->CloseElement();
  names_.pop_back();
}

void XmlWriter::Text(const std::string& name, const std::string& text) {
  Open(name);
  if (!text.empty()) printer_->PushText(text.c_str());
  Close();
}

void XmlWriter::CData(const std::string& name, const std::string& text) {
  Open(name);
  // "]]>" would end the section: each one ends a section after its "]]"
  // and the next starts with ">".
  size_t from = 0;
  while (true) {
    const size_t end = text.find("]]>", from);
    const std::string piece = text.substr(
        from, end == std::string::npos ? std::string::npos : end + 2 - from);
    printer_->PushText(piece.c_str(), true);
    if (end == std::string::npos) break;
    from = end + 2;
  }
  Close();
}

void XmlWriter::Number(const std::string& name, double value) {
  Text(name, FormatShortest(value));
}

void XmlWriter::Comment(const std::string& text) {
  printer_->PushComment(text.c_str());
}

std::string XmlWriter::str() const {
  return std::string(printer_->CStr(), printer_->CStrSize() - 1);
}

std::string FormatShortest(double value) { return fmt::format("{}", value); }

}  // namespace mrsim
