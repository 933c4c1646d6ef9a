#include "sim_core/scenario/scenario_xml.h"

#include <fmt/format.h>
#include <tinyxml2.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <type_traits>
#include <utility>
#include <vector>

#include "common/atomic_file.h"
#include "common/input_limits.h"
#include "common/trim.h"
#include "common/xml_error_text.h"
#include "sim_core/scenario/face_geometry.h"
#include "sim_core/scenario/scenario_schema_inl.h"
#include "sim_core/scenario/xml_writer.h"

namespace mrsim {
namespace {

namespace fs = std::filesystem;
using tinyxml2::XMLElement;

// No frame attribute, and the namespaces .NET's XmlSerializer writes: a
// file of the original MRSim (mrsim itself always writes frame=).
bool RootLooksOriginal(const tinyxml2::XMLElement* root) {
  return root->Attribute("frame") == nullptr &&
         root->Attribute("xmlns:xsi") != nullptr;
}

// Element and attribute names without a namespace prefix ("xsi:nil" ->
// "nil"): readers ignore namespaces.
std::string LocalName(const char* name) {
  const char* colon = std::strrchr(name, ':');
  return colon ? std::string(colon + 1) : std::string(name);
}

// XmlSerializer writes a null reference as xsi:nil="true".
bool IsNil(const XMLElement* x) {
  for (const tinyxml2::XMLAttribute* a = x->FirstAttribute(); a;
       a = a->Next()) {
    if (LocalName(a->Name()) == "nil" && Trim(a->Value()) == "true") {
      return true;
    }
  }
  return false;
}

const XMLElement* FirstChildNamed(const XMLElement* e, const char* name) {
  for (const XMLElement* c = e->FirstChildElement(); c;
       c = c->NextSiblingElement()) {
    if (LocalName(c->Name()) == name) return c;
  }
  return nullptr;
}

// The original wrote unused locks as <Joint> with no <type> and all-zero
// GUIDs (00000000-0000-0000-0000-000000000000) for the lock and both ends.
bool IsPlaceholderJoint(const XMLElement* e) {
  const XMLElement* type = FirstChildNamed(e, "type");
  if (type && Trim(type->GetText() ? type->GetText() : "") != "Lock") {
    return false;
  }
  for (const char* name : {"guid", "leftFrameGuid", "rightFrameGuid"}) {
    const XMLElement* g = FirstChildNamed(e, name);
    const std::string text = g && g->GetText() ? Trim(g->GetText()) : "";
    if (text.find_first_not_of("0-") != std::string::npos) return false;
  }
  return true;
}

// The element names a part may hold, from the schema. Optional parts may
// repeat as XmlSerializer's nil elements; lists without a wrapper repeat.
struct NameCollector {
  std::vector<std::string> single, repeated;
  template <typename T>
  void Field(const FieldInfo& info, T&) {
    single.push_back(info.xml);
  }
  template <typename P>
  void Child(const ChildInfo& info, P&) {
    single.push_back(info.xml);
  }
  template <typename P>
  void Optional(const ChildInfo& info, std::optional<P>&) {
    repeated.push_back(info.xml);
  }
  template <typename P, size_t N>
  void Array(const ChildInfo& info, std::array<P, N>&) {
    single.push_back(info.xml);
  }
  template <typename P>
  void List(const ChildInfo& info, std::vector<P>&) {
    (*info.item ? single : repeated).push_back(info.xml);
  }
  void Unsupported(const ChildInfo& info) { single.push_back(info.xml); }
};

template <typename P>
const NameCollector& NamesOf() {
  static const NameCollector names = [] {
    NameCollector c;
    P part;
    schema::Describe(c, part);
    return c;
  }();
  return names;
}

using ChildMap = std::map<std::string, std::vector<const XMLElement*>>;
using Items = std::vector<std::pair<const XMLElement*, std::string>>;

// Adds the lock the original meant by its placeholders: between each two
// consecutive modules (by mod_Nr) that no hinge, lock or sensor module
// joins yet, a lock between their nearest frames.
void AddDefaultLocks(Robot* robot) {
  std::map<std::string, std::string> parent;
  std::function<std::string(const std::string&)> root =
      [&](const std::string& x) -> std::string {
    auto it = parent.find(x);
    if (it == parent.end() || it->second == x) return x;
    return parent[x] = root(it->second);
  };
  auto join = [&](const std::string& a, const std::string& b) {
    parent[root(a)] = root(b);
  };
  std::set<std::string> named;
  for (const Module& m : robot->modules) {
    join(m.joint.left_frame_guid, m.joint.right_frame_guid);
    join(m.frames[0].guid, m.frames[1].guid);
  }
  for (const Joint& j : robot->locks) {
    join(j.left_frame_guid, j.right_frame_guid);
    named.insert(j.left_frame_guid);
    named.insert(j.right_frame_guid);
  }
  for (const SensorModule& sm : robot->sensor_modules) {
    if (named.count(sm.guid)) continue;
    for (const Module& m : robot->modules) {
      if (m.mod_nr == sm.left_mod_nr || m.mod_nr == sm.right_mod_nr) {
        join(m.frames[0].guid, sm.guid);
      }
    }
  }
  std::vector<const Module*> chain;
  for (const Module& m : robot->modules) chain.push_back(&m);
  std::stable_sort(
      chain.begin(), chain.end(),
      [](const Module* a, const Module* b) { return a->mod_nr < b->mod_nr; });
  for (size_t i = 0; i + 1 < chain.size(); ++i) {
    const Module& a = *chain[i];
    const Module& b = *chain[i + 1];
    if (root(a.frames[0].guid) == root(b.frames[0].guid)) continue;
    const Frame* best_a = &a.frames[0];
    const Frame* best_b = &b.frames[0];
    for (const Frame& fa : a.frames) {
      for (const Frame& fb : b.frames) {
        if ((fa.position - fb.position).norm() <
            (best_a->position - best_b->position).norm()) {
          best_a = &fa;
          best_b = &fb;
        }
      }
    }
    Joint lock;
    lock.guid = best_a->guid + "+" + best_b->guid;
    lock.type = JointType::kLock;
    lock.left_frame_guid = best_a->guid;
    lock.right_frame_guid = best_b->guid;
    robot->locks.push_back(lock);
    join(best_a->guid, best_b->guid);
  }
}

// In files the original MRSim wrote, a distance sensor looks along its
// ray_Direction; its face number (sensorPosition) was counted in the
// original's own way, which need not be mrsim's (docs/scenario.md, "Faces
// of the original's sensors"): a front sensor with ray (0, 0, 1) ahead of
// the chain is face 4 there, while mrsim's face 4 looks along the chain's
// axis. Each such sensor is put on the face its ray looks out of, so its
// ray starts where it leaves the module looking the same way it did in the
// original.
void PutRaysOnTheFacesTheyLookOutOf(std::vector<SensorModule>* modules) {
  for (SensorModule& sm : *modules) {
    for (DistanceSensor& d : sm.distance_sensors) {
      const Eigen::Vector3d& dir = d.ray_direction;
      if (d.sensor_position < 0 || d.sensor_position > 5 || !dir.allFinite() ||
          !(dir.norm() > 0) ||
          dir.dot(SensorFaceNormal(d.sensor_position)) > 0) {
        continue;  // looks out of its face, or left to the validator
      }
      int best = d.sensor_position;
      double best_dot = 0;
      for (int face = 0; face <= 5; ++face) {
        const double dot = dir.dot(SensorFaceNormal(face));
        if (dot > best_dot) {
          best = face;
          best_dot = dot;
        }
      }
      d.sensor_position = best;
    }
  }
}

class Reader {
 public:
  Reader(std::string file, std::string base_dir, ScenarioReadOptions options)
      : base_dir_(std::move(base_dir)), options_(options) {
    source_.file = std::move(file);
  }

  Scenario Read(const std::string& xml);

  [[noreturn]] void Fail(int line, const std::string& path,
                         const std::string& what) const {
    throw ScenarioError(source_.file, line, path, what);
  }
  [[noreturn]] void Fail(const XMLElement* e, const std::string& path,
                         const std::string& what) const {
    Fail(e ? e->GetLineNum() : 0, path, what);
  }
  void Note(const std::string& path, const XMLElement* e) {
    source_.lines.emplace(path, e->GetLineNum());
  }

  // What an omitted part or field means: the model's defaults, which are
  // Z-up and in metres whatever the file's frame and units.
  template <typename P>
  P Default(bool lock) const {
    P part{};
    if constexpr (std::is_same_v<P, Joint>) {
      if (lock) part.type = JointType::kLock;
    }
    return part;
  }

  template <typename P>
  void ReadPart(const XMLElement* e, const std::string& path, P* part,
                bool locks);
  template <typename T>
  void Parse(const XMLElement* e, const std::string& path,
             const FieldInfo& info, T* out) const;
  // Brings a value as the file gives it into the model's frame and units.
  template <typename T>
  void Convert(const FieldInfo& info, T* value) {
    to_model_.Field(info, *value);
  }
  Items ListItems(const XMLElement* wrapper, const std::string& path,
                  const char* item);

  int lock_placeholders_ = 0;  // in the robot being read

 private:
  std::string Text(const XMLElement* e, const std::string& path) const;
  double Number(const XMLElement* e, const std::string& path) const;
  ChildMap Children(const XMLElement* e, const std::string& path,
                    const NameCollector& names) const;

  std::string base_dir_;
  ScenarioReadOptions options_;
  FrameConvention frame_ = FrameConvention::kZUp;
  schema::GeometryMap to_model_;
  ScenarioSource source_;
};

// Reads the fields and children of one part element, as the schema lists
// them.
class ReadVisitor {
 public:
  ReadVisitor(Reader& reader, const XMLElement* element,
              const std::string& path, const ChildMap& children, bool locks)
      : r_(reader),
        e_(element),
        path_(path),
        children_(children),
        locks_(locks) {}

  template <typename T>
  void Field(const FieldInfo& info, T& value) {
    const std::string path = path_ + "/" + info.xml;
    const XMLElement* x = Find(info.xml);
    if (!x) {
      // In a list of locks a joint's type may be left out: it is a Lock.
      const bool waived = locks_ && std::strcmp(info.xml, "type") == 0;
      if (info.required && !waived) Missing(info.xml);
      return;
    }
    r_.Note(path, x);
    r_.Parse(x, path, info, &value);
    r_.Convert(info, &value);
  }

  template <typename P>
  void Child(const ChildInfo& info, P& part) {
    const XMLElement* x = Find(info.xml);
    if (!x) {
      if (info.required) Missing(info.xml);
      return;
    }
    r_.ReadPart(x, path_ + "/" + info.xml, &part, info.locks);
  }

  template <typename P>
  void Optional(const ChildInfo& info, std::optional<P>& part) {
    const std::string path = path_ + "/" + info.xml;
    const XMLElement* found = nullptr;
    for (const XMLElement* x : All(info.xml)) {
      if (IsNil(x)) continue;
      if (found) {
        r_.Fail(
            x, path,
            fmt::format("given twice (first at line {})", found->GetLineNum()));
      }
      found = x;
    }
    if (!found) return;
    if constexpr (std::is_same_v<P, Joint>) {
      if (info.locks && IsPlaceholderJoint(found)) {
        r_.Note(path, found);
        part.reset();  // the default lock: the plate is fixed to the module
        return;
      }
    }
    P value = r_.Default<P>(info.locks);
    r_.ReadPart(found, path, &value, info.locks);
    part = std::move(value);
  }

  template <typename P, size_t N>
  void Array(const ChildInfo& info, std::array<P, N>& parts) {
    const std::string path = path_ + "/" + info.xml;
    const XMLElement* wrapper = Find(info.xml);
    if (!wrapper) {
      if (info.required) Missing(info.xml);
      return;
    }
    const Items items = r_.ListItems(wrapper, path, info.item);
    if (items.size() != N) {
      r_.Fail(wrapper, path,
              fmt::format("expected {} <{}> elements, got {}", N, info.item,
                          items.size()));
    }
    for (size_t i = 0; i < N; ++i) {
      r_.ReadPart(items[i].first, items[i].second, &parts[i], info.locks);
    }
  }

  template <typename P>
  void List(const ChildInfo& info, std::vector<P>& parts) {
    Items items;
    if (*info.item) {
      const XMLElement* wrapper = Find(info.xml);
      if (!wrapper) {
        if (info.required) Missing(info.xml);
        return;
      }
      items = r_.ListItems(wrapper, path_ + "/" + info.xml, info.item);
    } else {
      const auto& all = All(info.xml);
      for (size_t i = 0; i < all.size(); ++i) {
        items.emplace_back(all[i],
                           fmt::format("{}/{}[{}]", path_, info.xml, i + 1));
      }
    }
    // Refused before any is read: a billion modules would be built first.
    if (items.size() > static_cast<size_t>(info.max_items)) {
      r_.Fail(items[info.max_items].first, items[info.max_items].second,
              ListLimitMessage(info));
    }
    for (size_t i = 0; i < items.size(); ++i) {
      const XMLElement* x = items[i].first;
      if constexpr (std::is_same_v<P, Joint>) {
        if (info.locks && IsPlaceholderJoint(x)) {
          // Only a robot's <locks> stand for locks between modules; the
          // sensors' placeholder locks mean what leaving them out means.
          if (std::strcmp(info.xml, "locks") == 0) ++r_.lock_placeholders_;
          continue;
        }
      }
      // Paths count the items kept, as the model (and so the validator)
      // does; the line still points at the element.
      const std::string path =
          *info.item ? fmt::format("{}/{}/{}[{}]", path_, info.xml, info.item,
                                   parts.size() + 1)
                     : items[i].second;
      P value = r_.Default<P>(info.locks);
      if constexpr (std::is_same_v<P, Robot>) r_.lock_placeholders_ = 0;
      r_.ReadPart(x, path, &value, info.locks);
      if constexpr (std::is_same_v<P, Robot>) {
        if (value.name.empty()) value.name = "robot" + std::to_string(i);
        if (r_.lock_placeholders_ > 0) AddDefaultLocks(&value);
      }
      parts.push_back(std::move(value));
    }
  }

  void Unsupported(const ChildInfo& info) {
    const XMLElement* x = Find(info.xml);
    if (!x) return;
    const std::string path = path_ + "/" + info.xml;
    r_.Note(path, x);
    for (const tinyxml2::XMLNode* n = x->FirstChild(); n;
         n = n->NextSibling()) {
      if (n->ToElement() || (n->ToText() && !Trim(n->Value()).empty())) {
        r_.Fail(x, path,
                fmt::format("mrsim does not model the original's mesh "
                            "terrain; expected an empty <{} /> (use "
                            "height_Image)",
                            info.xml));
      }
    }
  }

  bool Has(const char* name) const { return Find(name) != nullptr; }

 private:
  const XMLElement* Find(const char* name) const {
    auto it = children_.find(name);
    return it == children_.end() ? nullptr : it->second.front();
  }
  const std::vector<const XMLElement*>& All(const char* name) const {
    static const std::vector<const XMLElement*> kNone;
    auto it = children_.find(name);
    return it == children_.end() ? kNone : it->second;
  }
  [[noreturn]] void Missing(const char* name) const {
    r_.Fail(e_, path_ + "/" + name,
            fmt::format("missing; expected an element <{}>", name));
  }

  Reader& r_;
  const XMLElement* e_;
  const std::string& path_;
  const ChildMap& children_;
  bool locks_;
};

// Fields whose defaults depend on another field.
template <typename P>
void AfterRead(const ReadVisitor&, P*) {}

void AfterRead(const ReadVisitor& v, FluidRegion* r) {
  const FluidRegion water;
  if (!v.Has("density")) {
    r->density =
        r->kind == FluidKind::kWater ? water.density : FluidRegion::kAirDensity;
  }
  if (!v.Has("viscosity")) {
    r->viscosity = r->kind == FluidKind::kWater ? water.viscosity
                                                : FluidRegion::kAirViscosity;
  }
}

ChildMap Reader::Children(const XMLElement* e, const std::string& path,
                          const NameCollector& names) const {
  ChildMap children;
  auto listed = [](const std::vector<std::string>& list,
                   const std::string& name) {
    return std::find(list.begin(), list.end(), name) != list.end();
  };
  for (const XMLElement* child = e->FirstChildElement(); child;
       child = child->NextSiblingElement()) {
    const std::string name = LocalName(child->Name());
    const bool single = listed(names.single, name);
    if (!single && !listed(names.repeated, name)) {
      std::string expected;
      for (const auto* list : {&names.single, &names.repeated}) {
        for (const std::string& n : *list) {
          expected += (expected.empty() ? "<" : ", <") + n + ">";
        }
      }
      Fail(child, path + "/" + name,
           "unknown element; expected one of " +
               (expected.empty() ? std::string("(no children)") : expected));
    }
    auto& list = children[name];
    if (single && !list.empty()) {
      Fail(child, path + "/" + name,
           fmt::format("given twice (first at line {})",
                       list.front()->GetLineNum()));
    }
    list.push_back(child);
  }
  return children;
}

template <typename P>
void Reader::ReadPart(const XMLElement* e, const std::string& path, P* part,
                      bool locks) {
  Note(path, e);
  const ChildMap children = Children(e, path, NamesOf<P>());
  ReadVisitor visitor(*this, e, path, children, locks);
  schema::Describe(visitor, *part);
  AfterRead(visitor, part);
}

Items Reader::ListItems(const XMLElement* wrapper, const std::string& path,
                        const char* item) {
  Note(path, wrapper);
  Items items;
  for (const XMLElement* child = wrapper->FirstChildElement(); child;
       child = child->NextSiblingElement()) {
    const std::string name = LocalName(child->Name());
    if (name != item) {
      Fail(child, path + "/" + name,
           fmt::format("unknown element; expected one of <{}>", item));
    }
    if (IsNil(child)) continue;
    items.emplace_back(child,
                       fmt::format("{}/{}[{}]", path, item, items.size() + 1));
  }
  return items;
}

std::string Reader::Text(const XMLElement* e, const std::string& path) const {
  std::string text;
  for (const tinyxml2::XMLNode* n = e->FirstChild(); n; n = n->NextSibling()) {
    if (const XMLElement* child = n->ToElement()) {
      Fail(child, path,
           "expected text, got element <" + LocalName(child->Name()) + ">");
    }
    if (const tinyxml2::XMLText* t = n->ToText()) text += t->Value();
  }
  return text;
}

double Reader::Number(const XMLElement* e, const std::string& path) const {
  try {
    return ParseNumber(Text(e, path));
  } catch (const FieldError& err) {
    Fail(e, path, err.what());
  }
}

template <typename T>
void Reader::Parse(const XMLElement* e, const std::string& path,
                   const FieldInfo& info, T* out) const {
  if constexpr (std::is_same_v<T, Eigen::Vector3d> ||
                std::is_same_v<T, Eigen::Quaterniond>) {
    constexpr bool kQuat = std::is_same_v<T, Eigen::Quaterniond>;
    // The original wrote a frame's scale as one number: uniform.
    if (info.uniform_scalar && !e->FirstChildElement()) {
      const double s = Number(e, path);
      if constexpr (!kQuat) *out = Eigen::Vector3d(s, s, s);
      return;
    }
    static const NameCollector kXyz = [] {
      NameCollector c;
      c.single = {"x", "y", "z"};
      if (kQuat) c.single.push_back("w");
      return c;
    }();
    const ChildMap children = Children(e, path, kXyz);
    double v[4] = {0, 0, 0, 0};
    for (size_t i = 0; i < kXyz.single.size(); ++i) {
      const std::string& name = kXyz.single[i];
      auto it = children.find(name);
      if (it == children.end()) {
        Fail(e, path + "/" + name,
             "missing; expected an element <" + name + ">");
      }
      v[i] = Number(it->second.front(), path + "/" + name);
    }
    if constexpr (kQuat) {
      // (0, 0, 0, 0): the original's "no rotation given".
      *out = v[0] == 0 && v[1] == 0 && v[2] == 0 && v[3] == 0
                 ? Eigen::Quaterniond::Identity()
                 : Eigen::Quaterniond(v[3], v[0], v[1], v[2]);
    } else {
      *out = Eigen::Vector3d(v[0], v[1], v[2]);
    }
  } else {
    try {
      FieldRef(info, out).SetTextUnchecked(Text(e, path));
    } catch (const FieldError& err) {
      Fail(e, path, err.what());
    }
  }
}

Scenario Reader::Read(const std::string& xml) {
  const std::string& file = source_.file;
  try {
    // tinyxml2 parses recursively and keeps the whole tree: size and
    // nesting are checked first.
    CheckXmlLimits(xml, file);
  } catch (const InputLimitError& e) {
    throw ScenarioError(e.what());
  }
  tinyxml2::XMLDocument doc;
  if (doc.Parse(xml.data(), xml.size()) != tinyxml2::XML_SUCCESS) {
    // An empty file has no line to point at.
    const int line = doc.ErrorLineNum();
    throw ScenarioError(line > 0
                            ? fmt::format("{}:{}: Scenario: malformed XML: {}",
                                          file, line, XmlErrorText(doc))
                            : fmt::format("{}: {}", file, XmlErrorText(doc)));
  }
  const XMLElement* root = doc.RootElement();
  if (!root) {
    throw ScenarioError(file + ":1: Scenario: expected a <Scenario> element");
  }
  if (LocalName(root->Name()) != "Scenario") {
    Fail(root, LocalName(root->Name()), "expected the root element <Scenario>");
  }
  const std::string kRoot = "Scenario";
  std::optional<FrameConvention> said;
  for (const tinyxml2::XMLAttribute* a = root->FirstAttribute(); a;
       a = a->Next()) {
    if (std::string(a->Name()) != "frame") continue;  // xmlns:* and others
    const std::string value = a->Value();
    if (value == "z-up") {
      said = FrameConvention::kZUp;
    } else if (value == "unity-y-up") {
      said = FrameConvention::kUnityYUp;
    } else {
      Fail(root, kRoot + "/@frame",
           "expected frame=\"z-up\" or frame=\"unity-y-up\", got '" + value +
               "'");
    }
  }
  if (!said && !options_.frame && RootLooksOriginal(root)) {
    // What the original MRSim (Unity, .NET's XmlSerializer) wrote: read as
    // native it would be a robot ten or a hundred times too big, lying on
    // its side, and validate fine.
    Fail(root, kRoot + "/@frame",
         "no frame attribute, and the .NET namespaces of a file the original "
         "MRSim wrote (Unity's Y-up frame, usually centimetres): convert it "
         "with `mrsim-scenario convert --from unity-y-up FILE NATIVE.xml "
         "--scale 0.01`, or add frame=\"z-up\" to <Scenario> if it is "
         "already Z-up in metres");
  }
  if (said && options_.frame && *said != *options_.frame) {
    Fail(root, kRoot + "/@frame",
         fmt::format("the file says frame=\"{}\" but it was read as {}",
                     ToString(*said), ToString(*options_.frame)));
  }
  frame_ = said ? *said : options_.frame.value_or(FrameConvention::kZUp);
  if (!(options_.length_scale > 0) || !std::isfinite(options_.length_scale)) {
    throw std::invalid_argument(fmt::format(
        "length scale must be positive, got {}", options_.length_scale));
  }
  to_model_.swap_yz = frame_ == FrameConvention::kUnityYUp;
  to_model_.scale = options_.length_scale;
  Scenario s = Default<Scenario>(false);
  ReadPart(root, kRoot, &s, false);
  if (!said && frame_ == FrameConvention::kUnityYUp) {
    for (Robot& r : s.robots) PutRaysOnTheFacesTheyLookOutOf(&r.sensor_modules);
    PutRaysOnTheFacesTheyLookOutOf(&s.loose_sensor_modules);
  }
  s.base_dir = base_dir_;
  ValidateScenario(s, &source_);
  if (options_.source_out) *options_.source_out = source_;
  return s;
}

// Writes the fields and children of a part as the schema lists them.
class WriteVisitor {
 public:
  explicit WriteVisitor(XmlWriter& w) : w_(w) {}

  template <typename T>
  void Field(const FieldInfo& info, T& value) {
    if constexpr (std::is_same_v<T, Eigen::Vector3d>) {
      w_.Open(info.xml);
      w_.Number("x", value.x());
      w_.Number("y", value.y());
      w_.Number("z", value.z());
      w_.Close();
    } else if constexpr (std::is_same_v<T, Eigen::Quaterniond>) {
      w_.Open(info.xml);
      w_.Number("x", value.x());
      w_.Number("y", value.y());
      w_.Number("z", value.z());
      w_.Number("w", value.w());
      w_.Close();
    } else {
      const std::string text = FieldRef(info, &value).GetText();
      if (info.omit_when && text == info.omit_when) return;
      // A script reads as written, not as &lt; and &amp;.
      if (text.find('\n') != std::string::npos) {
        w_.CData(info.xml, text);
      } else {
        w_.Text(info.xml, text);
      }
    }
  }
  template <typename P>
  void Child(const ChildInfo& info, P& part) {
    Part(info.xml, part);
  }
  template <typename P>
  void Optional(const ChildInfo& info, std::optional<P>& part) {
    if (part) Part(info.xml, *part);
  }
  template <typename P, size_t N>
  void Array(const ChildInfo& info, std::array<P, N>& parts) {
    OpenWrapper(info);
    for (P& p : parts) Part(info.item, p);
    w_.Close();
  }
  template <typename P>
  void List(const ChildInfo& info, std::vector<P>& parts) {
    if (!*info.item) {
      for (P& p : parts) Part(info.xml, p);
      return;
    }
    if (parts.empty() && info.omit_when_empty) return;
    OpenWrapper(info);
    for (P& p : parts) Part(info.item, p);
    w_.Close();
  }
  void Unsupported(const ChildInfo&) {}

 private:
  template <typename P>
  void Part(const char* name, P& part) {
    w_.Open(name);
    schema::Describe(*this, part);
    w_.Close();
  }
  void OpenWrapper(const ChildInfo& info) {
    w_.Open(info.xml);
    if (info.assembly) w_.Attribute("xmlns", "Assembly");
  }

  XmlWriter& w_;
};

std::string Write(const Scenario& s, FrameConvention frame) {
  XmlWriter w;
  w.Open("Scenario");
  w.Attribute("xmlns:xsi", "http://www.w3.org/2001/XMLSchema-instance");
  w.Attribute("xmlns:xsd", "http://www.w3.org/2001/XMLSchema");
  w.Attribute("frame", ToString(frame));
  WriteVisitor visitor(w);
  // The visitor only reads; Describe takes parts by non-const reference
  // so one table serves readers and writers.
  schema::Describe(visitor, const_cast<Scenario&>(s));
  w.Close();
  return w.str();
}

}  // namespace

Scenario ReadScenarioString(const std::string& xml, const std::string& name,
                            const std::string& base_dir,
                            const ScenarioReadOptions& options) {
  return Reader(name, base_dir, options).Read(xml);
}

bool IsOriginalMrsimFile(const std::string& path) {
  std::optional<std::string> text;
  try {
    text = ReadFileAtMost(path);
    if (text) CheckXmlLimits(*text, path);
  } catch (const InputLimitError&) {
    return false;  // the reader says why
  }
  tinyxml2::XMLDocument doc;
  if (!text || doc.Parse(text->data(), text->size()) != tinyxml2::XML_SUCCESS) {
    return false;
  }
  const tinyxml2::XMLElement* root = doc.RootElement();
  return root != nullptr && LocalName(root->Name()) == "Scenario" &&
         RootLooksOriginal(root);
}

Scenario ReadScenarioFile(const std::string& path,
                          const ScenarioReadOptions& options) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    throw ScenarioError(path + ": is a folder, not a scenario file");
  }
  std::optional<std::string> bytes;
  try {
    bytes = ReadFileAtMost(path);
  } catch (const InputLimitError& e) {
    throw ScenarioError(e.what());
  }
  if (!bytes) {
    // No line: there is no file to point into.
    throw ScenarioError(path + ": cannot open the file (" +
                        std::strerror(errno) + ")");
  }
  // The files mrsim writes beside scenarios, given in their place: say so
  // rather than what the XML parser makes of them.
  const std::string& text = *bytes;
  if (text.rfind("mrsim-checkpoint ", 0) == 0) {
    throw ScenarioError(path +
                        ": is an mrsim-sim checkpoint, not a scenario; load "
                        "it with --load-checkpoint beside its scenario");
  }
  if (text.rfind("mrsim-opt-checkpoint ", 0) == 0) {
    throw ScenarioError(path +
                        ": is an mrsim-opt checkpoint, not a scenario; the "
                        "same mrsim-opt command again continues its run");
  }
  std::string dir = fs::path(path).parent_path().string();
  if (dir.empty()) dir = ".";
  return ReadScenarioString(text, path, dir, options);
}

std::string WriteScenarioString(const Scenario& scenario,
                                FrameConvention frame) {
  if (frame == FrameConvention::kZUp) return Write(scenario, frame);
  Scenario converted = scenario;
  ConvertZUpToUnity(&converted);
  return Write(converted, frame);
}

void WriteScenarioFile(const Scenario& scenario, const std::string& path,
                       FrameConvention frame) {
  WriteFileAtomically(path, WriteScenarioString(scenario, frame));
}

}  // namespace mrsim
