// mrsim-foxglove's flags and its run: LCM in the calling thread, the
// Foxglove WebSocket server (foxglove/foxglove_server.h) on its own.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <cstdio>
#include <string>

#include "lcmtypes/runtime/auth_flags.h"
#include "lcmtypes/runtime/signed_lcm.h"

namespace mrsim {

struct FoxgloveCommand {
  std::string lcm_url;
  std::string prefix = "MRSIM";
  AuthFlags auth;
  std::string control_key;  // a `mrsim keygen` file; empty: localhost only
  std::string bind = "0.0.0.0";
  int port = 8765;
  int max_clients = 64;
};

void AddFoxgloveFlags(CLI::App& app, FoxgloveCommand& command);

// Serves until SIGINT/SIGTERM (InstallStopHandlers first). Prints the
// address it listens on ("listening on ws://BIND:PORT") and, at the end,
// what it refused and dropped, on `err`. Throws std::runtime_error when it
// cannot listen or LCM fails, UsageError for a bad --control-key.
int RunFoxglove(const FoxgloveCommand& command, SignedLcm& lcm, std::FILE* err);

}  // namespace mrsim
