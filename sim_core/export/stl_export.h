// What `mrsim-scenario export-stl` and the studio's "Export STL" write to
// print a designed robot: one STL per distinct part at real scale (in
// millimetres, what slicers assume), each robot assembled in its start
// pose, and a parts list. Scene objects and the terrain are not parts.
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "sim_core/scenario/scenario.h"

namespace mrsim {

// One distinct part: parts are the same when kind, shape (box or mesh),
// size, mass and material are.
struct PrintedPart {
  std::string name;  // file stem, e.g. "module_frame_50x50x50mm_plastic"
  std::string kind;  // "module frame", "sensor module", "force plate",
                     // "loose frame", "distance sensor"
  std::string file;  // "<name>.stl"; "" for a bought part (distance sensor)
  Eigen::Vector3d size = Eigen::Vector3d::Zero();  // bounding box, m
  double mass = 0;                                 // kg, each
  std::string material;
  int count = 0;
};

struct StlExport {
  std::vector<PrintedPart> parts;  // in order of first appearance
  // File name (no directory) -> bytes: the parts' STLs, the assembled
  // robots ("<robot>_assembled.stl", "loose_parts_assembled.stl") and
  // "parts.csv".
  std::vector<std::pair<std::string, std::string>> files;
};

// Builds everything in memory. Mesh frames are read with
// scenario.base_dir. Throws std::runtime_error naming the frame whose mesh
// cannot be read, or std::invalid_argument when the scenario has no parts.
StlExport ExportStl(const Scenario& scenario);

// parts.csv: part,file,count,size_x_mm,size_y_mm,size_z_mm,mass_each_kg,
// mass_total_kg,material; one line per distinct part.
std::string PartsListCsv(const std::vector<PrintedPart>& parts);

// Writes the files into `dir` (made when missing), each atomically.
// Throws std::runtime_error naming the file that cannot be written.
void WriteStlExport(const StlExport& result, const std::string& dir);

}  // namespace mrsim
