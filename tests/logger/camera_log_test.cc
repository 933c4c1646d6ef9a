// Camera channels in the CSV logger: pictures in, a PNG sequence and an
// index per camera out, hostile pictures counted and dropped (in process:
// the Recorder, and mrsim-log's command replaying an .lcmlog).
#include <gtest/gtest.h>

#include <filesystem>
#include <lcm/lcm-cpp.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>
#include <vector>

#include "camera/camera_image_codec.h"
#include "logger/process/log_command.h"
#include "logger/recorder.h"
#include "tests/common/child_process.h"
#include "tests/logger/csv_reader.h"

namespace mrsim {
namespace {

namespace fs = std::filesystem;

// A picture whose every pixel is known from (seq, x, y).
CameraPicture KnownPicture(int64_t seq, int width = 32, int height = 24) {
  CameraPicture p;
  p.width = width;
  p.height = height;
  p.rgb.resize(static_cast<size_t>(width) * height * 3);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      uint8_t* px = &p.rgb[(static_cast<size_t>(y) * width + x) * 3];
      px[0] = static_cast<uint8_t>(x * 7 + seq);
      px[1] = static_cast<uint8_t>(y * 9);
      px[2] = static_cast<uint8_t>(200 - seq);
    }
  }
  return p;
}

camera_image_t KnownImage(int64_t seq, double sim_time, int camera,
                          int jpeg_quality = 0) {
  CameraImageHeader h;
  h.robot = "snake";
  h.sender = "mrsim-camera";
  h.camera = camera;
  h.name = "snake/sm0/camera";
  h.seq = seq;
  h.sim_time = sim_time;
  return EncodeCameraImage(h, KnownPicture(seq), jpeg_quality);
}

std::vector<uint8_t> Bytes(const camera_image_t& msg) {
  std::vector<uint8_t> b(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(b.data(), 0, static_cast<int>(b.size()));
  return b;
}

void Send(Recorder& rec, const std::string& channel,
          const camera_image_t& msg) {
  const auto b = Bytes(msg);
  rec.OnMessage(channel, b.data(), b.size());
}

// The PNG's pixels as RGB.
std::vector<uint8_t> ReadPng(const std::string& path) {
  const cv::Mat bgr = cv::imread(path, cv::IMREAD_COLOR);
  if (bgr.empty()) return {};
  std::vector<uint8_t> rgb;
  for (int y = 0; y < bgr.rows; ++y) {
    for (int x = 0; x < bgr.cols; ++x) {
      const cv::Vec3b& p = bgr.at<cv::Vec3b>(y, x);
      rgb.insert(rgb.end(), {p[2], p[1], p[0]});
    }
  }
  return rgb;
}

TEST(CameraLog, EachCameraBecomesPngsInOrderAndAnIndexOfSeqAndSimTime) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  const std::string dir = testing::TempDir("camera_log_pngs");
  {
    Recorder rec(registry, RecorderOptions{dir, {}});
    for (int k = 0; k < 3; ++k) {
      Send(rec, "MRSIM_CAMERA_snake", KnownImage(10 * k, 0.1 * k, 0));
      Send(rec, "MRSIM_CAMERA_snake", KnownImage(10 * k, 0.1 * k, 1));
    }
    rec.Flush();
    ASSERT_FALSE(rec.failed()) << rec.error();
    const auto stats = rec.Stats();
    ASSERT_EQ(stats.size(), 1u);
    EXPECT_EQ(stats[0].type, "mrsim.camera_image_t");
    EXPECT_EQ(stats[0].rows, 6);
    EXPECT_EQ(stats[0].missing, 0);
    EXPECT_EQ(stats[0].first_seq, 0);
    EXPECT_EQ(stats[0].last_seq, 20);
    EXPECT_EQ(stats[0].files.size(), 2u);
  }
  for (int camera = 0; camera < 2; ++camera) {
    const std::string folder = dir + "/camera_snake_" + std::to_string(camera);
    const auto index = testing::ReadCsvFile(folder + "/index.csv");
    ASSERT_EQ(index.header,
              (std::vector<std::string>{"seq", "sim_time", "file"}));
    ASSERT_EQ(index.rows.size(), 3u);
    for (int k = 0; k < 3; ++k) {
      EXPECT_EQ(index.rows[k][0], std::to_string(10 * k));
      EXPECT_DOUBLE_EQ(std::stod(index.rows[k][1]), 0.1 * k);
      const std::string file = "00000" + std::to_string(k) + ".png";
      EXPECT_EQ(index.rows[k][2], file);
      EXPECT_EQ(ReadPng(folder + "/" + file), KnownPicture(10 * k).rgb)
          << folder << "/" << file;
    }
  }
  // No temporary file is left beside the pictures.
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    EXPECT_EQ(e.path().extension() == ".tmp", false) << e.path();
  }
}

TEST(CameraLog, JpegPicturesAreWrittenAsPngsOfTheirSize) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  const std::string dir = testing::TempDir("camera_log_jpeg");
  {
    Recorder rec(registry, RecorderOptions{dir, {}});
    Send(rec, "MRSIM_CAMERA_snake", KnownImage(0, 0.0, 0, 90));
    rec.Flush();
    EXPECT_EQ(rec.Stats()[0].rows, 1);
  }
  const cv::Mat png = cv::imread(dir + "/camera_snake_0/000000.png");
  EXPECT_EQ(png.cols, 32);
  EXPECT_EQ(png.rows, 24);
}

TEST(CameraLog, HostilePicturesAreCountedAndDroppedAndTheRestWritten) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  const std::string dir = testing::TempDir("camera_log_hostile");
  std::vector<std::string> reports;
  RecorderOptions options{dir,
                          [&](const std::string& s) { reports.push_back(s); }};
  Recorder rec(registry, options);
  const std::string ch = "MRSIM_CAMERA_snake";
  Send(rec, ch, KnownImage(0, 0.0, 0));
  camera_image_t wrong_size = KnownImage(1, 0.1, 0);
  wrong_size.width = 40;  // 32x24 bytes claimed as 40x24
  Send(rec, ch, wrong_size);
  camera_image_t not_jpeg = KnownImage(2, 0.2, 0);
  not_jpeg.encoding = "jpeg";
  Send(rec, ch, not_jpeg);
  camera_image_t huge = KnownImage(3, 0.3, 0);
  huge.width = 100000;
  Send(rec, ch, huge);
  camera_image_t many = KnownImage(4, 0.4, 1 << 20);  // a folder per number?
  Send(rec, ch, many);
  camera_image_t forged_time = KnownImage(5, 0.5, 0);
  forged_time.sim_time = std::nan("");
  Send(rec, ch, forged_time);
  auto cut = Bytes(KnownImage(6, 0.6, 0));
  cut.resize(cut.size() / 2);
  rec.OnMessage(ch, cut.data(), cut.size());
  Send(rec, ch, KnownImage(7, 0.7, 0));
  rec.Flush();
  ASSERT_FALSE(rec.failed()) << rec.error();
  const ChannelStats s = rec.Stats()[0];
  EXPECT_EQ(s.messages, 8);
  EXPECT_EQ(s.malformed, 6);
  EXPECT_EQ(s.rows, 2);
  const auto index = testing::ReadCsvFile(dir + "/camera_snake_0/index.csv");
  ASSERT_EQ(index.rows.size(), 2u);
  EXPECT_EQ(index.rows[1][0], "7");
  EXPECT_FALSE(fs::exists(dir + "/camera_snake_1048576"));
  // The reason is named.
  bool named = false;
  for (const std::string& r : reports) {
    named = named || r.find("camera_image_t.data") != std::string::npos;
  }
  EXPECT_TRUE(named);
  EXPECT_NE(rec.Summary().find("6 malformed"), std::string::npos)
      << rec.Summary();
}

TEST(CameraLog, MissingPicturesAreCountedInCameraPeriodsAndResendsWrittenOnce) {
  const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  const std::string dir = testing::TempDir("camera_log_gaps");
  std::vector<std::string> reports;
  Recorder rec(registry, RecorderOptions{dir, [&](const std::string& s) {
                                           reports.push_back(s);
                                         }});
  const std::string ch = "MRSIM_CAMERA_snake";
  // A 10 Hz camera on a 100 Hz simulation: seq steps by 10 by design.
  for (int64_t seq : {0, 10, 20, 20, 50, 60}) {
    Send(rec, ch, KnownImage(seq, seq / 100.0, 0));
  }
  rec.Flush();
  const ChannelStats s = rec.Stats()[0];
  EXPECT_EQ(s.rows, 5);
  EXPECT_EQ(s.repeats, 1);
  EXPECT_EQ(s.gaps, 1);
  EXPECT_EQ(s.missing, 2);
  ASSERT_EQ(reports.size(), 1u);
  EXPECT_NE(reports[0].find("about 2 pictures missing between seq 20 and 50"),
            std::string::npos)
      << reports[0];
}

TEST(CameraLog, MrsimLogReplayWritesPicturesBesideTheCsvs) {
  const std::string dir = testing::TempDir("camera_log_replay");
  const std::string log_path = dir + "/run.lcmlog";
  {
    lcm::LogFile log(log_path, "w");
    ASSERT_TRUE(log.good());
    for (int k = 0; k < 4; ++k) {
      auto bytes = Bytes(KnownImage(5 * k, 0.05 * k, 0));
      lcm::LogEvent ev{};
      ev.eventnum = k;
      ev.timestamp = 1000 * k;
      ev.channel = "MRSIM_CAMERA_snake";
      ev.datalen = static_cast<int32_t>(bytes.size());
      ev.data = bytes.data();
      log.writeEvent(&ev);
    }
  }
  LogCommand command;
  command.from_log = log_path;
  command.out_dir = dir + "/out";
  std::FILE* err = std::tmpfile();
  ASSERT_EQ(RunLogCommand(command, PlanLog(command), nullptr, err), 0);
  std::fclose(err);
  const auto index =
      testing::ReadCsvFile(dir + "/out/camera_snake_0/index.csv");
  EXPECT_EQ(index.rows.size(), 4u);
  EXPECT_TRUE(fs::exists(dir + "/out/camera_snake_0/000003.png"));
  EXPECT_FALSE(fs::exists(dir + "/out/MRSIM_CAMERA_snake.csv"));
}

}  // namespace
}  // namespace mrsim
