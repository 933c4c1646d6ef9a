#include "nn_controller/process/nn_command_line.h"

#include <fmt/format.h>

#include "lcmtypes/runtime/channels.h"
#include "lcmtypes/runtime/version.h"

namespace mrsim {

void NnCommandLine::AddFlags(CLI::App& app) {
  app.set_version_flag("--version", VersionLine("mrsim-nn"));
  controller.AddFlags(
      app, {&options.prefix, &options.rate, &options.exit_with_sim},
      {"", "Control rate in Hz of sim time (0: answer every state)",
       "Exit when the simulator stops or has been silent for 5 s"});
  // The network reads the joint count from the state and needs no axes.
  for (const char* unused : {"--scenario", "--axes"}) {
    app.remove_option(app.get_option(unused));
  }
  app.add_option("--net", net_path,
                 "Network file (docs/nn.md), e.g. best_network.xml of "
                 "mrsim-opt --controller mlp:H")
      ->required();
  app.add_flag("--check", check_only,
               "Only read the network: report an error with its line "
               "(exit 2) or say it is fine (exit 0)");
}

void NnCommandLine::Finish() {
  net = ReadNetworkFile(net_path);
  controller.Finish("");
  options.robot = controller.robot;
  options.sender = controller.sender;
}

std::string NnCommandLine::StartLine() const {
  const MlpShape& s = net->network.shape();
  return fmt::format(
      "mrsim-nn: robot {}, sender {}, network {} ({} joints, hidden {}), "
      "listening on {}",
      options.robot, options.sender, net_path, s.joints,
      s.hidden.empty() ? "none" : HiddenLayersText(s.hidden),
      StateChannel(options.prefix, options.robot));
}

}  // namespace mrsim
