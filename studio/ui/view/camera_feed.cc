#include "studio/ui/view/camera_feed.h"

#include <GL/gl.h>

#include <algorithm>
#include <cmath>

#include "sim_core/scenario/sensor_face.h"

namespace mrsim::studio {

CameraFeed::CameraFeed() = default;

CameraFeed::~CameraFeed() {
  if (texture_ != 0) glDeleteTextures(1, &texture_);
}

void CameraFeed::SetModel(const mjModel* model, const Scenario& scenario,
                          long key) {
  // The chosen camera by what it is, not its place in the list: a camera
  // added in front of it keeps the picture on the same camera.
  std::string owner;
  int camera = -1;
  if (selected_ < static_cast<int>(cameras().size())) {
    owner = cameras()[selected_].owner;
    camera = cameras()[selected_].camera;
  }
  renderer_.reset();
  key_ = key;
  error_.clear();
  picture_ = FeedPicture();
  due_ = true;
  if (model == nullptr || ScenarioCameras(scenario).empty()) return;
  try {
    renderer_ = std::make_unique<CameraImageRenderer>(model, scenario);
  } catch (const std::exception& e) {
    error_ = std::string("no camera picture: ") + e.what();
    return;
  }
  const int found = renderer_->Find(owner, camera);
  selected_ = found >= 0 ? found : 0;
}

void CameraFeed::Clear() {
  renderer_.reset();
  key_ = -1;
  picture_ = FeedPicture();
  due_ = true;
}

const std::vector<ScenarioCamera>& CameraFeed::cameras() const {
  return renderer_ ? renderer_->cameras() : none_;
}

std::vector<std::string> CameraFeed::Labels() const {
  std::vector<std::string> labels;
  for (const ScenarioCamera& c : cameras()) {
    const int face = c.part.sensor_position;
    // A sensor module as the chain list names it (S<k>), a scene object
    // by its guid.
    const std::string part = c.scene_object >= 0
                                 ? c.part_guid
                                 : "S" + std::to_string(c.sensor_module);
    labels.push_back(
        c.owner + " camera " + std::to_string(c.camera) + ": " + part + " " +
        (face >= 0 && face < 6 ? kSensorFaceNames[face] : "?") + ", " +
        std::to_string(c.part.width) + "x" + std::to_string(c.part.height));
  }
  return labels;
}

void CameraFeed::Select(int index) {
  const int n = static_cast<int>(cameras().size());
  const int clamped = n == 0 ? 0 : std::clamp(index, 0, n - 1);
  if (clamped != selected_) due_ = true;
  selected_ = clamped;
}

bool CameraFeed::Update(mjData* data, double sim_time, std::int64_t seq) {
  if (!renderer_ || data == nullptr || cameras().empty()) return false;
  const ScenarioCamera& c = cameras()[selected_];
  // Time going back is a new run (or a reset): its frames start again.
  const bool restarted = picture_.seq >= 0 && sim_time < picture_.sim_time;
  if (!due_ && !restarted && sim_time < next_time_ - 1e-9) return false;
  try {
    renderer_->Render(selected_, data, seq, &picture_.rgb);
  } catch (const std::exception& e) {
    error_ = std::string("no camera picture: ") + e.what();
    return false;
  }
  error_.clear();
  picture_.camera = selected_;
  picture_.width = c.part.width;
  picture_.height = c.part.height;
  picture_.sim_time = sim_time;
  picture_.seq = seq;
  ++rendered_;
  due_ = false;
  // Frame k shows sim time k / rate: the next is the first after this one.
  const double rate = c.part.rate > 0 ? c.part.rate : 1;
  next_time_ = (std::floor(sim_time * rate + 1e-9) + 1) / rate;
  Upload();
  return true;
}

void CameraFeed::Upload() {
  GLint bound = 0, alignment = 4;
  glGetIntegerv(GL_TEXTURE_BINDING_2D, &bound);
  glGetIntegerv(GL_UNPACK_ALIGNMENT, &alignment);
  if (texture_ == 0) {
    glGenTextures(1, &texture_);
    glBindTexture(GL_TEXTURE_2D, texture_);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  } else {
    glBindTexture(GL_TEXTURE_2D, texture_);
  }
  // Rows of any width (3 bytes a pixel) are packed.
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB, picture_.width, picture_.height, 0,
               GL_RGB, GL_UNSIGNED_BYTE, picture_.rgb.data());
  glPixelStorei(GL_UNPACK_ALIGNMENT, alignment);
  glBindTexture(GL_TEXTURE_2D, static_cast<GLuint>(bound));
}

}  // namespace mrsim::studio
