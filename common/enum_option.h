// A command-line option whose value is a word of an EnumTable: the help
// lists the words, the default is printed by name, and a bad word is a
// usage error naming the flag and the valid words. For programs (CLI11);
// not installed.
#pragma once

#include <CLI/CLI.hpp>
#include <stdexcept>
#include <string>

#include "common/enum_table.h"

namespace mrsim {

template <typename E>
CLI::Option* AddEnumOption(CLI::App& app, const std::string& flag, E* value,
                           const EnumTable<E>& table, std::string help = "") {
  help = table.Choices(" | ") + (help.empty() ? "" : ": " + help);
  CLI::Option* option = app.add_option_function<std::string>(
      flag,
      [value, &table, flag](const std::string& text) {
        try {
          *value = table.Parse(text, flag);
        } catch (const std::invalid_argument& e) {
          throw CLI::ValidationError(e.what());
        }
      },
      help);
  option->default_str(table.Name(*value));
  return option;
}

}  // namespace mrsim
