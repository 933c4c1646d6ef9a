// Logs into columns: mrsim-log's CSV files and lcm-logger logs, the latter
// decoded with the logger's own flatteners (so a log reads into the same
// column names as the CSV mrsim-log would have written from it), and the
// messages of MCAP files (logger/mcap/mcap_reader.h, bounds-checked).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <charconv>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <lcm/lcm-cpp.hpp>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <regex>
#include <string>
#include <vector>

#include "camera/camera_image_codec.h"
#include "lcmtypes/runtime/decode.h"
#include "logger/csv_columns.h"
#include "logger/generic_flattener.h"
#include "logger/lcm_type_registry.h"
#include "logger/mcap/mcap_reader.h"
#include "logger/mcap/protobuf_json_decoder.h"
#include "logger/robot_state_flattener.h"
#include "python/src/bindings.h"

namespace py = pybind11;

namespace mrsim::python {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::optional<double> Number(const std::string& cell) {
  double v = 0;
  const char* end = cell.data() + cell.size();
  const auto r = std::from_chars(cell.data(), end, v);
  if (r.ec != std::errc() || r.ptr != end) return std::nullopt;
  return v;
}

// Columns filled row by row; a column first seen in a later row (a
// message whose shape changed) reads NaN ("" for text) before it.
class Table {
 public:
  void AddRow(const std::vector<std::string>& names,
              const std::vector<std::string>& cells) {
    for (size_t i = 0; i < names.size(); ++i) {
      Column& c = ColumnFor(names[i]);
      const std::string cell = i < cells.size() ? cells[i] : std::string();
      if (c.rows == rows_ + 1) continue;  // a repeated name: first wins
      Put(c, cell);
    }
    ++rows_;
    for (auto& [name, c] : columns_) {
      while (c.rows < rows_) Put(c, "");
    }
  }

  py::dict ToPython() const {
    py::dict d;
    for (const std::string& name : order_) {
      const Column& c = columns_.at(name);
      if (c.text) {
        d[py::str(name)] = c.strings;
      } else {
        d[py::str(name)] =
            py::array_t<double>(c.numbers.size(), c.numbers.data());
      }
    }
    return d;
  }

 private:
  struct Column {
    bool decided = false;
    bool text = false;
    std::vector<double> numbers;
    std::vector<std::string> strings;  // all cells, until decided numeric
    size_t rows = 0;
  };

  Column& ColumnFor(const std::string& name) {
    auto it = columns_.find(name);
    if (it != columns_.end()) return it->second;
    order_.push_back(name);
    Column& c = columns_[name];
    while (c.rows < rows_) Put(c, "");
    return c;
  }

  // A column is text when its first non-empty cell is not a number;
  // otherwise later cells that are not numbers read as NaN.
  static void Put(Column& c, const std::string& cell) {
    ++c.rows;
    if (!c.decided && !cell.empty()) {
      c.decided = true;
      c.text = !Number(cell).has_value();
      if (!c.text) {
        c.numbers.assign(c.strings.size(), kNaN);
        c.strings.clear();
      }
    }
    if (!c.decided || c.text) {
      c.strings.push_back(cell);
      return;
    }
    c.numbers.push_back(Number(cell).value_or(kNaN));
  }

  size_t rows_ = 0;
  std::vector<std::string> order_;
  std::map<std::string, Column> columns_;
};

py::dict ReadCsv(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw PlotInputError(path + ": cannot open");
  std::string line;
  if (!std::getline(in, line)) throw PlotInputError(path + ": empty file");
  if (!line.empty() && line.back() == '\r') line.pop_back();
  const std::vector<std::string> names = SplitCsvRecord(line);
  Table table;
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    const std::vector<std::string> cells = SplitCsvRecord(line);
    if (cells.size() != names.size()) {
      throw PlotInputError(path + ":" + std::to_string(number) + ": " +
                           std::to_string(cells.size()) +
                           " cells, the header has " +
                           std::to_string(names.size()));
    }
    table.AddRow(names, cells);
  }
  return table.ToPython();
}

int64_t Fingerprint(const uint8_t* data, size_t size) {
  if (size < 8) return 0;
  uint64_t h = 0;
  for (int i = 0; i < 8; ++i) h = (h << 8) | data[i];
  return static_cast<int64_t>(h);
}

// The pictures of a camera channel (camera_image_t), checked and decoded
// by the camera codec: each picture an (H, W, 3) uint8 array in column
// "image" beside the message's other fields.
struct CameraColumns {
  std::vector<CameraImageHeader> headers;
  std::vector<std::string> encodings;
  std::vector<CameraPicture> pictures;
  std::vector<double> utimes;
  std::vector<double> log_times;

  // False when the message does not decode or its picture is malformed.
  bool Add(const uint8_t* data, size_t size, double log_time) {
    camera_image_t m;
    if (!DecodeMessage(data, size, &m)) return false;
    try {
      pictures.push_back(DecodeCameraImage(m));
    } catch (const std::exception&) {
      return false;
    }
    headers.push_back(CameraImageHeaderOf(m));
    encodings.push_back(m.encoding);
    utimes.push_back(static_cast<double>(m.utime));
    log_times.push_back(log_time);
    return true;
  }

  py::dict ToPython() const {
    const auto numbers = [&](auto field) {
      std::vector<double> v;
      for (const CameraImageHeader& h : headers) {
        v.push_back(static_cast<double>(field(h)));
      }
      return py::array_t<double>(v.size(), v.data());
    };
    const auto texts = [&](auto field) {
      py::list v;
      for (const CameraImageHeader& h : headers) v.append(field(h));
      return v;
    };
    py::dict d;
    d["utime"] = py::array_t<double>(utimes.size(), utimes.data());
    d["seq"] = numbers([](const CameraImageHeader& h) { return h.seq; });
    d["robot"] = texts([](const CameraImageHeader& h) { return h.robot; });
    d["sender"] = texts([](const CameraImageHeader& h) { return h.sender; });
    d["camera"] = numbers([](const CameraImageHeader& h) { return h.camera; });
    d["sensor_module"] =
        numbers([](const CameraImageHeader& h) { return h.sensor_module; });
    d["name"] = texts([](const CameraImageHeader& h) { return h.name; });
    d["sim_time"] =
        numbers([](const CameraImageHeader& h) { return h.sim_time; });
    std::vector<double> widths, heights;
    py::list images;
    for (const CameraPicture& p : pictures) {
      widths.push_back(p.width);
      heights.push_back(p.height);
      py::array_t<std::uint8_t> a({static_cast<py::ssize_t>(p.height),
                                   static_cast<py::ssize_t>(p.width),
                                   py::ssize_t{3}});
      std::copy(p.rgb.begin(), p.rgb.end(), a.mutable_data());
      images.append(a);
    }
    d["width"] = py::array_t<double>(widths.size(), widths.data());
    d["height"] = py::array_t<double>(heights.size(), heights.data());
    d["encoding"] = encodings;
    d["image"] = images;
    d["log_time"] = py::array_t<double>(log_times.size(), log_times.data());
    return d;
  }
};

py::dict ReadLcmLog(const std::string& path, const std::string& channels) {
  lcm::LogFile log(path, "r");
  if (!log.good()) throw PlotInputError(path + ": cannot open as an LCM log");
  static const LcmTypeRegistry registry = LcmTypeRegistry::WithBuiltinTypes();
  const std::regex wanted(channels.empty() ? ".*" : channels);
  struct Channel {
    std::unique_ptr<MessageFlattener> flattener;
    int64_t hash = 0;
    Table table;
    std::unique_ptr<CameraColumns> camera;  // a camera_image_t channel
    int64_t undecoded = 0;
  };
  std::map<std::string, Channel> by_channel;
  std::vector<std::string> order;
  FlatRow row;
  int64_t events = 0;
  {
    py::gil_scoped_release release;
    while (const lcm::LogEvent* e = log.readNextEvent()) {
      ++events;
      if (!std::regex_match(e->channel, wanted) || e->datalen < 0) continue;
      const auto* data = static_cast<const uint8_t*>(e->data);
      const size_t size = static_cast<size_t>(e->datalen);
      const int64_t hash = Fingerprint(data, size);
      auto it = by_channel.find(e->channel);
      if (it == by_channel.end()) {
        it = by_channel.emplace(e->channel, Channel{}).first;
        order.push_back(e->channel);
      }
      Channel& ch = it->second;
      if (hash == camera_image_t::getHash()) {
        if (!ch.camera) ch.camera = std::make_unique<CameraColumns>();
        if (!ch.camera->Add(data, size,
                            static_cast<double>(e->timestamp) / 1e6)) {
          ++ch.undecoded;
        }
        continue;
      }
      if (!ch.flattener || ch.hash != hash) {
        const LcmStruct* type = registry.FindByHash(hash);
        if (type == nullptr) {
          ++ch.undecoded;
          continue;
        }
        if (type->full_name() == "mrsim.robot_state_t") {
          ch.flattener = std::make_unique<RobotStateFlattener>(registry);
        } else {
          ch.flattener = std::make_unique<GenericFlattener>(registry, *type);
        }
        ch.hash = hash;
      }
      if (!ch.flattener->Flatten(data, size, &row)) {
        ++ch.undecoded;
        continue;
      }
      std::vector<std::string> names = ch.flattener->columns();
      std::vector<std::string> cells = SplitCsvRecord(row.values);
      names.push_back("log_time");
      cells.push_back(std::to_string(static_cast<double>(e->timestamp) / 1e6));
      ch.table.AddRow(names, cells);
    }
  }
  if (events == 0) {
    std::ifstream in(path, std::ios::binary | std::ios::ate);
    if (in && in.tellg() > 0) {
      throw PlotInputError(path + ": not an LCM log (no event found)");
    }
  }
  py::dict out;
  for (const std::string& name : order) {
    const Channel& ch = by_channel.at(name);
    if (ch.camera) {
      out[py::str(name)] = ch.camera->ToPython();
      continue;
    }
    py::dict columns = ch.table.ToPython();
    out[py::str(name)] = columns;
  }
  return out;
}

// Every message of an MCAP file by topic: its log times (s) and data (JSON
// text: as mrsim-log --mcap-encoding json writes it, protobuf messages
// decoded into the same text), with the schema's name and whether the file
// was finished (false: cut off after its last whole chunk).
py::tuple ReadMcapMessages(const std::string& path,
                           const std::string& channels) {
  struct Topic {
    std::vector<double> times;
    std::vector<std::string> data;
  };
  std::map<std::string, Topic> topics;
  std::vector<std::string> order;
  mcap::McapSummary summary;
  {
    py::gil_scoped_release release;
    std::ifstream in(path, std::ios::binary);
    if (!in) throw PlotInputError(path + ": cannot open");
    const std::string bytes((std::istreambuf_iterator<char>(in)),
                            std::istreambuf_iterator<char>());
    const std::regex wanted(channels.empty() ? ".*" : channels);
    mcap::McapJsonPayloads payloads;
    try {
      summary = mcap::ReadMcap(bytes, path, [&](const mcap::McapMessage& m) {
        const std::string& topic = m.channel->topic;
        auto it = topics.find(topic);
        if (it == topics.end()) {
          if (!std::regex_match(topic, wanted)) return;
          it = topics.emplace(topic, Topic{}).first;
          order.push_back(topic);
        }
        Topic& t = it->second;
        t.times.push_back(static_cast<double>(m.log_time) / 1e9);
        t.data.emplace_back(payloads.Text(m));
      });
    } catch (const mcap::McapError& e) {
      throw PlotInputError(e.what());
    }
  }
  py::dict out;
  for (const std::string& name : order) {
    const Topic& t = topics.at(name);
    std::string schema;
    for (const auto& [id, c] : summary.channels) {
      if (c.topic != name) continue;
      const auto s = summary.schemas.find(c.schema_id);
      if (s != summary.schemas.end()) schema = s->second.name;
    }
    py::list data;
    for (const std::string& d : t.data) data.append(py::str(d));
    out[py::str(name)] = py::make_tuple(
        schema, py::array_t<double>(t.times.size(), t.times.data()), data);
  }
  return py::make_tuple(out, summary.complete);
}

}  // namespace

void BindLogs(py::module_& m) {
  m.def("read_csv", &ReadCsv, py::arg("path"), R"doc(
One CSV file as mrsim-log writes it: a dict from column name to a numpy
float array (text columns such as 'robot' as lists of str). Raises LogError
naming the file and line of a malformed row.)doc");
  m.def("read_lcm_log", &ReadLcmLog, py::arg("path"), py::arg("channels") = "",
        R"doc(
An lcm-logger log: {channel: {column: array}} with the column names
mrsim-log gives (decoded by the logger's flatteners), plus 'log_time' (s,
when the message was logged). A camera channel (camera_image_t) has the
message's fields and 'image': a list of (H, W, 3) uint8 arrays, JPEGs
decoded. channels: a regex of the channels to read (default all).
Messages of unknown types or that do not decode (a picture whose sizes,
bytes or JPEG disagree among them) are left out. Raises LogError when the file is not an LCM log.)doc");
  m.def("read_mcap_messages", &ReadMcapMessages, py::arg("path"),
        py::arg("channels") = "",
        R"doc(
The messages of an MCAP file (as mrsim-log --mcap writes it, or any):
({topic: (schema_name, log_times_s, [data as JSON str])}, complete);
protobuf messages are decoded with their schema into the JSON the json
encoding writes. complete
is False for a file cut off after its last whole chunk (its writer was
killed). channels: a regex of the topics to read (default all). Every
length is checked and every CRC the file has; raises LogError naming the
byte offset of what is malformed. mrsim.read_mcap turns it into columns.)doc");
}

}  // namespace mrsim::python
