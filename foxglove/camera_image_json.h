// camera_image_t as Foxglove sees it: a checked picture as
// foxglove.RawImage (rgb8) or foxglove.CompressedImage (jpeg) JSON, with
// the bytes in base64 as Foxglove's JSON encoding wants them, and the
// message itself for its generic JSON channel without the bytes (the
// generated writer would spell each byte as a number: ~4 characters a
// byte, 3.5 MB for one 640x480 picture).
#pragma once

#include <cstdint>
#include <string_view>

#include "lcmtypes/json/json_writer.h"
#include "mrsim/camera_image_t.hpp"

namespace mrsim::foxglove {

// The Foxglove schema name for a picture of this encoding.
const char* FoxgloveImageSchemaName(const camera_image_t& msg);
// ... and its JSON Schema.
const char* FoxgloveImageSchema(const camera_image_t& msg);

// Writes the foxglove.RawImage or foxglove.CompressedImage of `msg`, which
// DecodeCameraImage has accepted; frame_id is the MuJoCo camera's name.
void WriteFoxgloveImageJson(const camera_image_t& msg, uint64_t timestamp_ns,
                            JsonWriter& out);

// Writes `msg` as its generated JSON, but with `data` empty (num_bytes
// still says how many bytes the picture has).
void WriteCameraImageWithoutBytes(const camera_image_t& msg, JsonWriter& out);
// The generated JSON Schema of camera_image_t, saying that `data` is left
// empty and where the picture is.
const char* CameraImageWithoutBytesSchema();

// Writes `bytes` as a JSON string of their base64 (RFC 4648, padded).
void WriteBase64String(std::string_view bytes, JsonWriter& out);

}  // namespace mrsim::foxglove
