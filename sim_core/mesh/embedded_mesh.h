// A mesh file carried inside a scenario, so a scenario sent to another
// process (the optimiser's workers) needs no files: Frame::shape is then
// "base64:<the file's bytes in base64>:<file name>". The file name keeps
// the format (.stl, .obj) for MuJoCo and the scenario reader.
#pragma once

#include <string>
#include <vector>

namespace mrsim {

struct EmbeddedMesh {
  std::string file_name;  // e.g. "link.stl"
  std::vector<unsigned char> bytes;
};

bool IsEmbeddedMesh(const std::string& shape);

// The shape string for the mesh file at `path`. Throws std::runtime_error
// naming the path when it cannot be read.
std::string EmbedMeshFile(const std::string& path);

// Throws std::runtime_error on a malformed shape string.
EmbeddedMesh DecodeEmbeddedMesh(const std::string& shape);

}  // namespace mrsim
