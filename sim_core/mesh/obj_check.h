// A strict reading of an OBJ mesh's text before MuJoCo sees it: MuJoCo
// 2.2's OBJ loader trusts the file (a face index past the last vertex
// writes past its buffers), so every statement and index is checked here
// first, against what the file defines.
#pragma once

#include <cstddef>
#include <string>

namespace mrsim {

// Throws std::runtime_error "line N: <what was expected>" unless every line
// is blank, a comment, or one of v (3 to 7 finite numbers), vt, vn, f (at
// least three corners `v`, `v/vt`, `v//vn` or `v/vt/vn`, each index non-zero
// and naming a vertex, texture or normal the file has; when the file has
// normals, every corner names one), o, g, s or usemtl;
// at least one face. mtllib and other statements are refused (MuJoCo would
// ignore or, worse, open them).
void CheckObjText(const char* data, std::size_t size);

}  // namespace mrsim
