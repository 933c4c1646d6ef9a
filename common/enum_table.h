// The one table of an enum's words: each value with the name a user types
// (flags, settings files, checkpoints, messages). Parse and print go through
// it, so a value is added in one row and a bad word is refused with the
// field it was given for and every valid word ("selection: expected
// tournament or truncation, got 'best'").
#pragma once

#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace mrsim {

template <typename E>
class EnumTable {
 public:
  struct Entry {
    E value;
    const char* name;
  };

  // `field`: what an error names when no other field is given to Parse.
  EnumTable(std::string field, std::initializer_list<Entry> entries)
      : field_(std::move(field)), entries_(entries) {}
  EnumTable(std::string field, std::vector<Entry> entries)
      : field_(std::move(field)), entries_(std::move(entries)) {}

  // The value's word; "?" for a value not in the table (a cast integer).
  const char* Name(E value) const {
    for (const Entry& e : entries_) {
      if (e.value == value) return e.name;
    }
    return "?";
  }

  std::optional<E> Find(const std::string& text) const {
    for (const Entry& e : entries_) {
      if (text == e.name) return e.value;
    }
    return std::nullopt;
  }

  // Throws std::invalid_argument "<field>: expected a, b or c, got 'x'"
  // (field empty: the table's).
  E Parse(const std::string& text, const std::string& field = "") const {
    if (const std::optional<E> value = Find(text)) return *value;
    throw std::invalid_argument((field.empty() ? field_ : field) +
                                ": expected " + Choices() + ", got '" + text +
                                "'");
  }

  // Every word in table order.
  std::vector<std::string> Names() const {
    std::vector<std::string> names;
    for (const Entry& e : entries_) names.emplace_back(e.name);
    return names;
  }

  // "a, b or c" (separator empty), or the words joined by `separator`
  // ("a | b | c" for a flag's help).
  std::string Choices(const std::string& separator = "") const {
    std::string text;
    for (size_t i = 0; i < entries_.size(); ++i) {
      if (i > 0) {
        text += !separator.empty()         ? separator
                : i + 1 == entries_.size() ? std::string(" or ")
                                           : std::string(", ");
      }
      text += entries_[i].name;
    }
    return text;
  }

  const std::string& field() const { return field_; }
  const std::vector<Entry>& entries() const { return entries_; }

 private:
  std::string field_;
  std::vector<Entry> entries_;
};

}  // namespace mrsim
