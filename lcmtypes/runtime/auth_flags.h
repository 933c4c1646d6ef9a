// --key-file and --accept-replays, the same on every program that talks
// LCM (docs/security.md). For programs only: it pulls in CLI11.
#pragma once

#include <CLI/CLI.hpp>
#include <iostream>
#include <string>

#include "lcmtypes/runtime/message_key.h"
#include "lcmtypes/runtime/signed_lcm.h"

namespace mrsim {

inline void AddAuthFlags(CLI::App& app, AuthFlags& flags) {
  app.add_option("--key-file", flags.key_file,
                 "Sign every message with this key and drop unsigned, "
                 "forged and replayed ones (default: $MRSIM_KEY_FILE; none: "
                 "unsigned; mrsim keygen PATH writes one)");
  app.add_flag("--accept-replays", flags.accept_replays,
               "With a key: take signed messages whatever their timestamp "
               "(a log played back with lcm-logplayer)");
}

// A SignedLcm's warnings as lines "PROGRAM: ..." on `out`.
inline SignedLcm::Warn WarnLines(std::ostream& out, std::string program) {
  return [&out, program](const std::string& line) {
    out << program << ": " << line << std::endl;
  };
}

}  // namespace mrsim
