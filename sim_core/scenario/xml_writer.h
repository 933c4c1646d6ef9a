// Deterministic XML text in the layout .NET's XmlSerializer wrote: the
// declaration, two-space indentation, "<name />" for empty elements, every
// string escaped, numbers in the shortest form that reads back exactly.
// One writer for scenario, genome and gait files (tinyxml2's XMLPrinter).
#pragma once

#include <deque>
#include <memory>
#include <string>

namespace mrsim {

class XmlWriter {
 public:
  XmlWriter();  // writes <?xml version="1.0" encoding="utf-8"?>
  ~XmlWriter();
  XmlWriter(const XmlWriter&) = delete;
  XmlWriter& operator=(const XmlWriter&) = delete;

  // Elements nest: Open, then Attribute calls, then children, then Close.
  void Open(const std::string& name);
  void Attribute(const std::string& name, const std::string& value);
  void Attribute(const std::string& name, double value);
  void Close();
  // <name>text</name>, or <name /> when text is empty.
  void Text(const std::string& name, const std::string& text);
  // <name><![CDATA[text]]></name>, so multi-line text (a script) reads
  // as written; text holding "]]>" is split over two CDATA sections.
  void CData(const std::string& name, const std::string& text);
  void Number(const std::string& name, double value);
  void Comment(const std::string& text);

  // The document so far.
  std::string str() const;

 private:
  class Printer;
  std::unique_ptr<Printer> printer_;
  std::deque<std::string> names_;  // of the open elements
};

// The shortest decimal text that reads back to the same double.
std::string FormatShortest(double value);

}  // namespace mrsim
