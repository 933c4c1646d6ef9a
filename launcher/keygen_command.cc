#include "launcher/keygen_command.h"

#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

#include "common/cli_exit.h"
#include "lcmtypes/runtime/message_key.h"
#include "lcmtypes/runtime/usage_error.h"

namespace mrsim {

int RunKeygen(int argc, char** argv) {
  CLI::App app{
      "mrsim keygen: write a new key for signed messages (mode 0600). Copy "
      "it to every host of the network and pass it with --key-file or "
      "MRSIM_KEY_FILE (docs/security.md)."};
  std::string path;
  app.add_option("path", path, "Key file to write (must not exist)")
      ->required();
  try {
    app.parse(argc - 1, argv + 1);
  } catch (const CLI::ParseError& e) {
    return CliParseExit(app, e);
  }
  try {
    WriteKeyFile(path);
  } catch (const UsageError& e) {
    std::cerr << "mrsim keygen: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "mrsim keygen: " << e.what() << "\n";
    return 1;
  }
  std::cout << "wrote " << path
            << " (mode 0600); use it on every host: --key-file " << path
            << " or MRSIM_KEY_FILE=" << path << "\n";
  return 0;
}

void ExportLaunchKey(const std::string& key_file) {
  if (key_file.empty()) return;
  const AuthFlags auth{key_file};
  auth.Load();
  auth.ExportToChildren();
}

}  // namespace mrsim
