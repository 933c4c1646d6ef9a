// The JSON Schemas of the Foxglove message types mrsim-foxglove sends
// (foxglove.SceneUpdate, foxglove.FrameTransforms: the parts of them it
// fills; foxglove.RawImage, foxglove.CompressedImage) and of its services'
// requests and responses. Foxglove draws a channel of schema name
// foxglove.SceneUpdate in its 3-D panel; the schema text tells it (and any
// client) the fields.
#pragma once

namespace mrsim::foxglove {

extern const char* const kSceneUpdateSchema;
extern const char* const kFrameTransformsSchema;
// A camera picture: raw rgb8 pixels, or a JPEG file; data is base64.
extern const char* const kRawImageSchema;
extern const char* const kCompressedImageSchema;
// A control service's request with no argument, with `steps`, with `speed`.
extern const char* const kEmptyRequestSchema;
extern const char* const kStepRequestSchema;
extern const char* const kSpeedRequestSchema;
// Every control service's response: {"ok": bool, "message": string}.
extern const char* const kControlResponseSchema;

}  // namespace mrsim::foxglove
