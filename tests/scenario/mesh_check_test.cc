#include "sim_core/mesh/mesh_check.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "sim_core/mesh/obj_check.h"

namespace mrsim {
namespace {

using ::testing::HasSubstr;

const char kCube[] =
    "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\n"
    "v -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n"
    "f 1 3 2\nf 1 4 3\nf 5 6 7\nf 5 7 8\nf 1 2 6\nf 1 6 5\n"
    "f 2 3 7\nf 2 7 6\nf 3 4 8\nf 3 8 7\nf 4 1 5\nf 4 5 8\n";

std::string ObjError(const std::string& text) {
  try {
    CheckObjText(text.data(), text.size());
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

std::string Replace(std::string s, const std::string& from,
                    const std::string& to) {
  s.replace(s.find(from), from.size(), to);
  return s;
}

std::vector<unsigned char> Bytes(const std::string& s) {
  return std::vector<unsigned char>(s.begin(), s.end());
}

TEST(ObjCheck, TakesTheFormsOfFaceCornersOBJWrites) {
  EXPECT_EQ(ObjError(kCube), "");
  EXPECT_EQ(ObjError("# a comment\no tet\ng body\ns off\nusemtl steel\n"
                     "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\r\n"
                     "vt 0 0\nvt 1 0\nvt 0 1\nvn 0 0 1\n"
                     "f 1/1/1 3/3/1 2/2/1\nf 1//1 2//1 4//1\n"
                     "f -4/-3/1 -1/-2/1 -2/-1/1\nf 2/1/1 3//1 4//1 1//1\n"),
            "");
}

// MuJoCo 2.2's OBJ loader writes past its buffers on such a face (found by
// fuzzing): the line is named before MuJoCo sees the file.
TEST(ObjCheck, AFaceIndexPastTheLastVertexIsRefusedWithItsLine) {
  EXPECT_THAT(ObjError(Replace(kCube, "f 4 5 8", "f 4 5 9")),
              HasSubstr("line 20: face corner '9': no vertex 9 (the file has "
                        "8)"));
  EXPECT_THAT(ObjError(Replace(kCube, "f 1 3 2", "f 0 3 2")),
              HasSubstr("line 9: face corner '0': expected a non-zero index"));
  EXPECT_THAT(ObjError(Replace(kCube, "f 1 3 2", "f -9 3 2")),
              HasSubstr("line 9: face corner '-9': no vertex -9"));
  EXPECT_THAT(ObjError(Replace(kCube, "f 1 3 2", "f 1/1 3 2")),
              HasSubstr("no texture coordinate 1 (the file has 0)"));
  EXPECT_THAT(ObjError(Replace(kCube, "f 1 3 2", "f 1//2 3 2")),
              HasSubstr("no normal 2 (the file has 0)"));
  // With normals in the file, MuJoCo 2.2 reads one for every corner.
  EXPECT_THAT(ObjError(std::string("vn 0 0 1\n") + kCube),
              HasSubstr("line 10: face corner '1': the file has normals"));
}

TEST(ObjCheck, RefusesWhatIsNotAMeshStatement) {
  EXPECT_THAT(ObjError(std::string("mtllib other.mtl\n") + kCube),
              HasSubstr("line 1: 'mtllib' is not an OBJ statement"));
  EXPECT_THAT(ObjError(Replace(kCube, "v 1 1 1", "v 1 nan 1")),
              HasSubstr("line 7: 'nan' is not a number"));
  EXPECT_THAT(ObjError(Replace(kCube, "v 1 1 1", "v 1 1")),
              HasSubstr("line 7: 'v' needs 3 to 7 numbers"));
  EXPECT_THAT(ObjError(Replace(kCube, "f 1 3 2", "f 1 3")),
              HasSubstr("line 9: a face needs at least three corners"));
  EXPECT_THAT(ObjError("v 0 0 0\n"), HasSubstr("no faces"));
  EXPECT_THAT(ObjError(std::string("v 0 0 0\0\n", 9)), HasSubstr("NUL"));
}

TEST(MeshCheck, MujocosOwnReaderJudgesWhatOurReadingLetsThrough) {
  const Eigen::Vector3d scale(0.01, 0.01, 0.01);
  EXPECT_NO_THROW(CheckMeshReadable(Bytes(kCube), "cube.obj", scale));
  // Flat: no volume, which MuJoCo cannot give a mass.
  try {
    CheckMeshReadable(Bytes("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"), "flat.obj",
                      scale);
    FAIL() << "a mesh without volume passed";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("volume"));
  }
  try {
    CheckMeshReadable(Bytes(Replace(kCube, "f 4 5 8", "f 4 5 9")), "cube.obj",
                      scale);
    FAIL() << "a face past the last vertex passed";
  } catch (const std::runtime_error& e) {
    EXPECT_THAT(e.what(), HasSubstr("cube.obj: line 20"));
  }
}

}  // namespace
}  // namespace mrsim
