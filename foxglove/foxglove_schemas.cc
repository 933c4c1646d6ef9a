#include "foxglove/foxglove_schemas.h"

namespace mrsim::foxglove {

#define MRSIM_TIME_SCHEMA                                                   \
  R"({"type":"object","properties":{"sec":{"type":"integer","minimum":0},)" \
  R"("nsec":{"type":"integer","minimum":0,"maximum":999999999}}})"
#define MRSIM_VECTOR3_SCHEMA                                 \
  R"({"type":"object","properties":{"x":{"type":"number"},)" \
  R"("y":{"type":"number"},"z":{"type":"number"}}})"
#define MRSIM_QUATERNION_SCHEMA                              \
  R"({"type":"object","properties":{"x":{"type":"number"},)" \
  R"("y":{"type":"number"},"z":{"type":"number"},"w":{"type":"number"}}})"
#define MRSIM_POSE_SCHEMA                                              \
  R"({"type":"object","properties":{"position":)" MRSIM_VECTOR3_SCHEMA \
  R"(,"orientation":)" MRSIM_QUATERNION_SCHEMA "}}"
#define MRSIM_COLOR_SCHEMA                                   \
  R"({"type":"object","properties":{"r":{"type":"number"},)" \
  R"("g":{"type":"number"},"b":{"type":"number"},"a":{"type":"number"}}})"
#define MRSIM_SHAPE_SCHEMA                                                              \
  R"({"type":"array","items":{"type":"object","properties":{"pose":)" MRSIM_POSE_SCHEMA \
  R"(,"size":)" MRSIM_VECTOR3_SCHEMA R"(,"color":)" MRSIM_COLOR_SCHEMA "}}}"

const char* const kSceneUpdateSchema =
    R"({"title":"foxglove.SceneUpdate","type":"object","properties":{)"
    R"("deletions":{"type":"array","items":{"type":"object","properties":{)"
    R"("timestamp":)" MRSIM_TIME_SCHEMA
    R"(,"type":{"type":"integer","enum":[0,1]},"id":{"type":"string"}}}},)"
    R"("entities":{"type":"array","items":{"type":"object","properties":{)"
    R"("timestamp":)" MRSIM_TIME_SCHEMA
    R"(,"frame_id":{"type":"string"},"id":{"type":"string"},)"
    R"("lifetime":)" MRSIM_TIME_SCHEMA R"(,"frame_locked":{"type":"boolean"},)"
    R"("metadata":{"type":"array","items":{"type":"object","properties":{)"
    R"("key":{"type":"string"},"value":{"type":"string"}}}},)"
    R"("cubes":)" MRSIM_SHAPE_SCHEMA R"(,"spheres":)" MRSIM_SHAPE_SCHEMA
    "}}}}}";

const char* const kFrameTransformsSchema =
    R"({"title":"foxglove.FrameTransforms","type":"object","properties":{)"
    R"("transforms":{"type":"array","items":{"type":"object","properties":{)"
    R"("timestamp":)" MRSIM_TIME_SCHEMA
    R"(,"parent_frame_id":{"type":"string"},"child_frame_id":{"type":"string"},)"
    R"("translation":)" MRSIM_VECTOR3_SCHEMA
    R"(,"rotation":)" MRSIM_QUATERNION_SCHEMA "}}}}}";

const char* const kRawImageSchema =
    R"({"title":"foxglove.RawImage","type":"object","properties":{)"
    R"("timestamp":)" MRSIM_TIME_SCHEMA R"(,"frame_id":{"type":"string"},)"
    R"("width":{"type":"integer","minimum":0},)"
    R"("height":{"type":"integer","minimum":0},)"
    R"("encoding":{"type":"string"},)"
    R"("step":{"type":"integer","minimum":0},)"
    R"("data":{"type":"string","contentEncoding":"base64"}}})";

const char* const kCompressedImageSchema =
    R"({"title":"foxglove.CompressedImage","type":"object","properties":{)"
    R"("timestamp":)" MRSIM_TIME_SCHEMA R"(,"frame_id":{"type":"string"},)"
    R"("data":{"type":"string","contentEncoding":"base64"},)"
    R"("format":{"type":"string"}}})";

const char* const kEmptyRequestSchema = R"({"type":"object","properties":{}})";
const char* const kStepRequestSchema =
    R"({"type":"object","properties":{"steps":{"type":"integer","minimum":1,)"
    R"("description":"control periods to advance, default 1"}}})";
const char* const kSpeedRequestSchema =
    R"({"type":"object","properties":{"speed":{"type":"number",)"
    R"("exclusiveMinimum":0,"description":"real-time factor"}},)"
    R"("required":["speed"]})";
const char* const kControlResponseSchema =
    R"({"type":"object","properties":{"ok":{"type":"boolean"},)"
    R"("message":{"type":"string"}}})";

#undef MRSIM_TIME_SCHEMA
#undef MRSIM_VECTOR3_SCHEMA
#undef MRSIM_QUATERNION_SCHEMA
#undef MRSIM_POSE_SCHEMA
#undef MRSIM_COLOR_SCHEMA
#undef MRSIM_SHAPE_SCHEMA

}  // namespace mrsim::foxglove
