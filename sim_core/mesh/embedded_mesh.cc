#include "sim_core/mesh/embedded_mesh.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>

#include "sim_core/mesh/base64.h"

namespace mrsim {
namespace {
constexpr char kPrefix[] = "base64:";
constexpr size_t kPrefixSize = sizeof(kPrefix) - 1;
}  // namespace

bool IsEmbeddedMesh(const std::string& shape) {
  return shape.compare(0, kPrefixSize, kPrefix) == 0;
}

std::string EmbedMeshFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read mesh file '" + path + "'");
  std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  const std::string name = std::filesystem::path(path).filename().string();
  if (name.find(':') != std::string::npos) {
    throw std::runtime_error("mesh file name '" + name +
                             "' contains ':', which cannot be embedded");
  }
  // The file name last: the shape still ends in the mesh's extension.
  return kPrefix + Base64Encode(bytes) + ":" + name;
}

EmbeddedMesh DecodeEmbeddedMesh(const std::string& shape) {
  const size_t colon = shape.rfind(':');
  if (!IsEmbeddedMesh(shape) || colon < kPrefixSize ||
      colon + 1 == shape.size()) {
    throw std::runtime_error(
        "embedded mesh: expected base64:<bytes>:<file name>, got '" +
        shape.substr(0, 40) + "'");
  }
  EmbeddedMesh mesh;
  mesh.file_name = shape.substr(colon + 1);
  mesh.bytes = Base64Decode(shape.substr(kPrefixSize, colon - kPrefixSize));
  if (mesh.bytes.empty()) {
    throw std::runtime_error("embedded mesh '" + mesh.file_name +
                             "' has no bytes");
  }
  return mesh;
}

}  // namespace mrsim
