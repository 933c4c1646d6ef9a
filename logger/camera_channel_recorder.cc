#include "logger/camera_channel_recorder.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

#include "common/hash.h"
#include "lcmtypes/runtime/decode.h"

namespace mrsim {

CameraChannelRecorder::CameraChannelRecorder(std::string out_dir,
                                             std::string stem)
    : out_dir_(std::move(out_dir)), stem_(std::move(stem)) {}

void CameraChannelRecorder::Record(const uint8_t* data, size_t size,
                                   ChannelLedger& ledger) {
  WireError wire;
  if (!DecodeMessage(data, size, &msg_, &wire)) {
    ledger.Malformed(size, std::string(wire.field) + ": " + wire.problem);
    return;
  }
  if (msg_.camera < 0 || msg_.camera >= kMaxCameras) {
    ledger.Malformed(size, "camera " + std::to_string(msg_.camera) +
                               ", expected 0.." +
                               std::to_string(kMaxCameras - 1));
    return;
  }
  if (!std::isfinite(msg_.sim_time) || msg_.sim_time < 0) {
    ledger.Malformed(size, "sim_time is not a time");
    return;
  }
  CameraPicture picture;
  try {
    picture = DecodeCameraImage(msg_);
  } catch (const std::invalid_argument& e) {
    ledger.Malformed(size, e.what());
    return;
  }
  ChannelStats& stats = ledger.stats();
  Camera& cam = cameras_[msg_.camera];
  const uint64_t hash = Fnv1a64(picture.rgb.data(), picture.rgb.size());
  // A lockstep simulator re-sends the states it waits for, and a camera may
  // answer one again with the same picture: written once.
  if (cam.have_last && msg_.seq == cam.last_seq && hash == cam.last_hash) {
    ++stats.repeats;
    return;
  }
  int64_t missing = 0;
  std::string gap;
  if (cam.have_last) {
    const double step = msg_.sim_time - cam.last_time;
    if (step <= 0) {
      cam.period = 0;  // a reset: the period is found again
    } else {
      if (cam.period > 0 && step > 1.5 * cam.period) {
        missing = std::llround(step / cam.period) - 1;
        char text[200];
        std::snprintf(text, sizeof(text),
                      "camera %d: about %lld pictures missing between seq "
                      "%lld and %lld (sim time %.6g to %.6g s)",
                      msg_.camera, static_cast<long long>(missing),
                      static_cast<long long>(cam.last_seq),
                      static_cast<long long>(msg_.seq), cam.last_time,
                      msg_.sim_time);
        gap = text;
      }
      cam.period = cam.period > 0 ? std::min(cam.period, step) : step;
    }
  }
  ledger.TakeSparseSeq(msg_.seq, missing, gap);
  if (!cam.writer) {
    cam.writer = std::make_unique<CameraPictureWriter>(
        out_dir_ + "/" + stem_ + "_" + std::to_string(msg_.camera));
    stats.files.push_back(cam.writer->index_path());
  }
  cam.writer->Write(msg_.seq, msg_.sim_time, picture);
  ++stats.rows;
  cam.have_last = true;
  cam.last_seq = msg_.seq;
  cam.last_time = msg_.sim_time;
  cam.last_hash = hash;
}

void CameraChannelRecorder::Flush() {
  for (auto& [k, cam] : cameras_) {
    if (cam.writer) cam.writer->Flush();
  }
}

std::string CameraChannelRecorder::Folder(int camera) const {
  auto it = cameras_.find(camera);
  if (it == cameras_.end() || !it->second.writer) return "";
  return it->second.writer->folder();
}

}  // namespace mrsim
