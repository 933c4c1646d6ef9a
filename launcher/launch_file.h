// A launch file: which mrsim processes to start, with what arguments, and
// which of them ends the run when it exits. XML, with ${variables}:
//
//   <launch name="demo">
//     <arg name="out" default="out/demo"/>
//     <arg name="lcm_url" env="LCM_DEFAULT_URL" default="udpm://..."/>
//     <hub port="7667"/>   (LCM's TCP hub; optional, put it first)
//     <process name="sim" program="mrsim-sim" required="true"
//              args="${launch_dir}/../scenarios/case_study.xml --duration 20"/>
//     <process name="viewer" program="mrsim-view" ready="listening on"
//              finish="120" args="... --out ${out}/demo.mp4 --exit-with-sim"/>
//   </launch>
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace mrsim {

// A bad launch file; what() names the file, line and what was expected.
class LaunchError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ProcessSpec {
  std::string name;
  std::string program;  // a name looked up on the search path, or a path
  std::vector<std::string> args;  // after variable substitution and splitting
  bool required = false;          // when it exits, the whole launch stops
  bool enabled = true;            // enabled="false" or --without leaves it out
  double delay_s = 0.0;           // start this long after the previous process
  // > 0: when a required process ends, this one may go on for up to this
  // long to finish its work by itself (a viewer rendering the frames it
  // fell behind on, a logger writing its last rows) before it is stopped.
  // A stop the user asks for (Ctrl-C) still stops it at once.
  double finish_s = 0.0;
  // > 0: the processes after it start only once this TCP port on this host
  // accepts connections (a hub: LCM's tcpq clients do not retry).
  int ready_port = 0;
  // Not empty: the processes after it start only once it has printed a
  // line this regular expression finds (ECMAScript, searched anywhere in
  // the line), e.g. "listening on": a viewer or logger that takes a while
  // to set up under load would otherwise miss the run's first seconds.
  std::string ready_line;
  // A hub: its siblings talk through it, so it is stopped after all of
  // them (and the terminal's Ctrl-C does not reach it), which spares them
  // "connection reset" and "re-connecting" on a normal stop.
  bool stop_last = false;
  int line = 0;  // where it was declared, for messages
};

struct LaunchFile {
  std::string path;
  std::string name;
  std::map<std::string, std::string> variables;  // after overrides
  std::vector<ProcessSpec> processes;            // in start order
};

// Reads and checks a launch file. An <arg>'s value is its override (an
// override for an undeclared arg is an error), else the environment
// variable its env attribute names when set, else its default. A <hub>
// becomes a process running LCM's TCPService from the lcm jar. Built-in
// variables:
// ${launch_dir} (the file's directory) and ${cwd}.
LaunchFile ReadLaunchFile(const std::string& path,
                          const std::map<std::string, std::string>& overrides);

// Splits a command line on white space, honouring '...' and "..." quotes.
// Throws std::invalid_argument on an unterminated quote.
std::vector<std::string> SplitArgs(const std::string& text);

}  // namespace mrsim
