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
  const std::string name = typed.substr(0, typed.find('='));
  std::vector<std::string> names;
  CollectNames(app, &names);
  std::string best;
  size_t best_distance = std::max<size_t>(2, name.size() / 3) + 1;
  for (const std::string& candidate : names) {
    const size_t d = EditDistance(name, candidate);
    if (d < best_distance) {
      best_distance = d;
      best = candidate;
    }
  }
  return best;
}

int CliParseExit(const CLI::App& app, const CLI::ParseError& error,
                 std::ostream& out, std::ostream& err) {
  if (error.get_exit_code() == 0) return app.exit(error, out, err) == 0 ? 0 : 2;
  if (dynamic_cast<const CLI::ExtrasError*>(&error) == nullptr) {
    app.exit(error, out, err);
    return 2;
  }
  const std::string program =
      std::filesystem::path(app.get_name()).filename().string();
  const std::vector<std::string> extras = app.remaining(true);
  err << (program.empty() ? "" : program + ": ") << "unexpected argument"
      << (extras.size() == 1 ? "" : "s") << ":";
  for (const std::string& e : extras) err << " " << e;
  err << "\n";
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
