// `mrsim keygen PATH`: writes a new message key (docs/security.md).
#pragma once

#include <string>

namespace mrsim {

// Parses `mrsim keygen ...` (argv[1] is "keygen"), writes the key and
// returns the exit status, having printed what happened.
int RunKeygen(int argc, char** argv);

// `mrsim launch --key-file PATH`: checks the key (UsageError naming the
// file) and hands it to every process started, as MRSIM_KEY_FILE. Empty:
// nothing.
void ExportLaunchKey(const std::string& key_file);

}  // namespace mrsim
