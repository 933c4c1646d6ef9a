#include "common/cli_exit.h"

#include <algorithm>
#include <filesystem>
#include <vector>

#include "common/edit_distance.h"

namespace mrsim {
namespace {

void CollectNames(const CLI::App& app, std::vector<std::string>* names) {
  for (const CLI::Option* option : app.get_options()) {
    for (const std::string& l : option->get_lnames())
      names->push_back("--" + l);
    for (const std::string& s : option->get_snames()) names->push_back("-" + s);
  }
  for (const CLI::App* sub : app.get_subcommands({})) {
    CollectNames(*sub, names);
  }
}

}  // namespace

std::string NearestOption(const CLI::App& app, const std::string& typed) {
  std::vector<std::string> names;
  CollectNames(app, &names);
  return NearestWord(typed.substr(0, typed.find('=')), names);
}

std::string NearestSubcommand(const CLI::App& app, const std::string& typed) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands({})) {
    names.push_back(sub->get_name());
  }
  return NearestWord(typed, names);
}

int CliParseExit(const CLI::App& app, const CLI::ParseError& error,
                 std::ostream& out, std::ostream& err) {
  if (error.get_exit_code() == 0) return app.exit(error, out, err) == 0 ? 0 : 2;
  if (dynamic_cast<const CLI::ExtrasError*>(&error) == nullptr) {
    app.exit(error, out, err);
    // "A subcommand is required" when the word meant as one is mistyped.
    const std::vector<std::string> rest = app.remaining(true);
    if (!rest.empty() && !rest[0].empty() && rest[0][0] != '-' &&
        app.get_subcommands().empty()) {
      const std::string nearest = NearestSubcommand(app, rest[0]);
      if (!nearest.empty()) {
        err << "  " << rest[0] << ": did you mean " << nearest << "?\n";
      }
    }
    return 2;
  }
  const std::string program =
      std::filesystem::path(app.get_name()).filename().string();
  const std::vector<std::string> extras = app.remaining(true);
  err << (program.empty() ? "" : program + ": ") << "unexpected argument"
      << (extras.size() == 1 ? "" : "s") << ":";
  for (const std::string& e : extras) err << " " << e;
  err << "\n";
  // A word where a subcommand was expected: the first extra, when no
  // subcommand was given ("mrsim-scenario valdate x.xml").
  if (!extras.empty() && !extras[0].empty() && extras[0][0] != '-' &&
      app.get_subcommands().empty()) {
    const std::string nearest = NearestSubcommand(app, extras[0]);
    if (!nearest.empty()) {
      err << "  " << extras[0] << ": did you mean " << nearest << "?\n";
    }
  }
  for (const std::string& e : extras) {
    if (e.size() < 2 || e[0] != '-' || (e[1] >= '0' && e[1] <= '9')) continue;
    const std::string nearest = NearestOption(app, e);
    if (!nearest.empty()) {
      err << "  " << e.substr(0, e.find('=')) << ": did you mean " << nearest
          << "?\n";
    }
  }
  err << "Run with --help for more information.\n";
  return 2;
}

}  // namespace mrsim
