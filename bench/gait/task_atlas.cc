#include "bench/gait/task_atlas.h"

#include "optimizer/episode/task.h"

namespace mrsim {

std::vector<AtlasEntry> TaskAtlasEntries() {
  std::vector<AtlasEntry> entries;
  for (const std::string& name : TaskNames()) {
    const Task task = MakeTask(name);
    AtlasEntry e;
    e.name = "task-" + name;
    e.source = "task";
    e.robot = "pitch-yaw x12 " + name;
    e.gait = task.gait;
    e.trial.world = task.scenario;
    e.trial.chain.modules = kTaskModules;  // for the body length
    e.trial.chain.pattern = ChainPattern::kPitchYaw;
    e.trial.seconds = task.duration;
    entries.push_back(e);
  }
  return entries;
}

const std::vector<AtlasEntry>& AllAtlasEntries() {
  static const std::vector<AtlasEntry> kAll = [] {
    std::vector<AtlasEntry> all = AtlasEntries();
    for (AtlasEntry& e : TaskAtlasEntries()) all.push_back(e);
    return all;
  }();
  return kAll;
}

}  // namespace mrsim
