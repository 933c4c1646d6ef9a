// Who may call mrsim-foxglove's control services (pause, resume, step,
// speed, reset). Watching is open to every client; controlling is for
// clients on this host, or, when mrsim-foxglove has a control key, for
// clients that give its token in the URL (ws://host:port/?token=HEX),
// wherever they are.
#pragma once

#include <string>
#include <string_view>

namespace mrsim::foxglove {

// The token of a key file written by `mrsim keygen`: its key as hex.
// Throws UsageError as ReadKeyFile does.
std::string ControlTokenFromKeyFile(const std::string& path);

// `query`: the URL's query ("token=ab12&x=y"); `token`: the control key's
// token, empty when there is none.
bool MayControl(bool from_loopback, std::string_view query,
                const std::string& token);

}  // namespace mrsim::foxglove
