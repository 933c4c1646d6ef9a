// mrsim-ctl: drive a running simulation and its gait controllers from the
// shell; the commands and their conversations are in tools/ctl_client.h
// (`mrsim-ctl --help` lists them).
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <iostream>
#include <string>
#include <vector>

#include "common/cli_exit.h"
#include "common/lcm_url.h"
#include "lcmtypes/runtime/auth_flags.h"
#include "lcmtypes/runtime/usage_error.h"
#include "lcmtypes/runtime/version.h"
#include "tools/ctl_client.h"

int main(int argc, char** argv) {
  CLI::App app{mrsim::CtlHelp()};
  app.set_version_flag("--version", mrsim::VersionLine("mrsim-ctl"));
  std::string lcm_url;
  mrsim::CtlOptions options;
  std::vector<std::string> words;
  app.add_option("--lcm-url", lcm_url, "LCM URL (default: LCM's default)");
  mrsim::AuthFlags auth;
  mrsim::AddAuthFlags(app, auth);
  app.add_option("--prefix", options.prefix, "Channel prefix")
      ->capture_default_str();
  app.add_option("--timeout", options.timeout,
                 "Seconds to wait for the other side's heartbeat and answer")
      ->capture_default_str();
  // Options may come after the command too (`status --prefix X`); a
  // negative number stays a word (`direction -1 0`).
  app.add_option("command", words, "The command and its arguments")->required();
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return mrsim::CliParseExit(app, e);
  }
  try {
    options.sender = "mrsim-ctl-" + std::to_string(getpid());
    mrsim::SignedLcm lcm(lcm_url, auth.Load(),
                         mrsim::WarnLines(std::cerr, "mrsim-ctl"));
    if (!lcm.good()) {
      std::cerr << "mrsim-ctl: " << mrsim::CannotOpenLcm(lcm_url) << "\n";
      return 1;
    }
    return mrsim::RunCtl(lcm, words, options, std::cout, std::cerr);
  } catch (const std::exception& e) {
    std::cerr << "mrsim-ctl: " << e.what() << "\n";
    // A bad key file or bad words are bad usage; anything else a failure.
    const bool usage = dynamic_cast<const mrsim::UsageError*>(&e) ||
                       dynamic_cast<const std::invalid_argument*>(&e);
    return usage ? 2 : 1;
  }
}
