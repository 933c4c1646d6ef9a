// The shared secret of a signed mrsim network, in a key file: `mrsim keygen
// PATH` writes one (32 random bytes as hex, mode 0600), every program reads
// it with --key-file PATH or the MRSIM_KEY_FILE environment variable. A key
// file readable by group or others is refused (docs/security.md).
#pragma once

#include <string>

namespace mrsim {

inline constexpr const char* kKeyFileEnv = "MRSIM_KEY_FILE";

// How a program signs and checks its messages. An empty key: it signs
// nothing and refuses nothing (as without security).
struct AuthConfig {
  std::string key;              // the secret bytes; empty: unsigned
  std::string key_file;         // where it came from (for messages)
  bool accept_replays = false;  // take old timestamps (lcm-logplayer)
  bool enabled() const { return !key.empty(); }
};

// Writes a new random key to `path` with mode 0600. Throws UsageError when
// the file exists or cannot be written.
void WriteKeyFile(const std::string& path);

// Reads a key file. Throws UsageError naming the path when it is missing,
// readable or writable by group or others, not a key, or shorter than 16
// bytes.
std::string ReadKeyFile(const std::string& path);

// The key of --key-file `flag`, else of $MRSIM_KEY_FILE, else none.
AuthConfig LoadAuthConfig(const std::string& flag, bool accept_replays);

// What --key-file and --accept-replays set (auth_flags.h adds them).
struct AuthFlags {
  std::string key_file;
  bool accept_replays = false;

  // Throws UsageError naming the key file when it cannot be used.
  AuthConfig Load() const { return LoadAuthConfig(key_file, accept_replays); }
  // Hands --key-file to the programs this one starts, as MRSIM_KEY_FILE.
  void ExportToChildren() const;
};

}  // namespace mrsim
