// Makes a scenario self-contained: every mesh file a frame names and the
// terrain's height image become their bytes in base64 inside the scenario
// (embedded_mesh.h, Scene::height_image "base64:..."), as the original
// MRSim's files carried them. Then the file opens and runs on another
// computer with nothing beside it. Reading embedded assets back is the
// scenario reader's (their lengths checked there).
#pragma once

#include <string>

#include "sim_core/scenario/scenario.h"

namespace mrsim {

// Embeds in place; relative paths resolve against scenario.base_dir.
// Already embedded assets and box/primitive frames are left alone. Throws
// std::runtime_error naming the frame (or the scene's heightImage) and the
// file when one cannot be read or is longer than kMaxInputFileBytes.
void EmbedAssetFiles(Scenario& scenario);

// Whether any mesh frame or the terrain's height image names a file
// rather than carrying its bytes: a file saved without embedding (the
// studio shows "Embed terrain and meshes" as the file was saved).
bool NamesAssetFiles(const Scenario& scenario);

}  // namespace mrsim
