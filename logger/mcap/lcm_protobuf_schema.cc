#include "logger/mcap/lcm_protobuf_schema.h"

#include <google/protobuf/descriptor.pb.h>

#include <map>
#include <set>
#include <stdexcept>
#include <vector>

namespace mrsim {
namespace {

namespace pb = google::protobuf;
using Field = pb::FieldDescriptorProto;

// The protobuf type of one element of an LCM primitive.
Field::Type ScalarType(const std::string& type) {
  if (type == "int8_t" || type == "int16_t" || type == "int32_t") {
    return Field::TYPE_SINT32;
  }
  if (type == "int64_t") return Field::TYPE_INT64;
  if (type == "byte") return Field::TYPE_UINT32;
  if (type == "boolean") return Field::TYPE_BOOL;
  if (type == "float") return Field::TYPE_FLOAT;
  if (type == "double") return Field::TYPE_DOUBLE;
  return Field::TYPE_STRING;
}

std::string Qualified(const std::string& full_name) { return "." + full_name; }

// Sets `f` to hold one row (the last dimension) of member `m`, or the
// member itself when it is not an array.
void SetElement(const LcmMember& m, bool array, Field* f) {
  if (IsLcmPrimitive(m.type)) {
    if (array && m.type == "byte") {
      f->set_type(Field::TYPE_BYTES);
      f->set_label(Field::LABEL_OPTIONAL);
      return;
    }
    f->set_type(ScalarType(m.type));
  } else {
    f->set_type(Field::TYPE_MESSAGE);
    f->set_type_name(Qualified(m.type));
  }
  f->set_label(array ? Field::LABEL_REPEATED : Field::LABEL_OPTIONAL);
}

void AddMessage(const LcmStruct& s, pb::FileDescriptorProto* file) {
  pb::DescriptorProto* msg = file->add_message_type();
  msg->set_name(s.name);
  for (size_t i = 0; i < s.members.size(); ++i) {
    const LcmMember& m = s.members[i];
    Field* f = msg->add_field();
    f->set_name(m.name);
    f->set_json_name(m.name);
    f->set_number(static_cast<int>(i + 1));
    if (m.dims.size() <= 1) {
      SetElement(m, !m.dims.empty(), f);
      continue;
    }
    // NAME_row1 holds a row of the first dimension, and so on; the last
    // wrapper holds the elements.
    const std::string outer = Qualified(s.full_name());
    f->set_type(Field::TYPE_MESSAGE);
    f->set_label(Field::LABEL_REPEATED);
    f->set_type_name(outer + "." + m.name + kProtobufRowSuffix + "1");
    for (size_t level = 1; level < m.dims.size(); ++level) {
      pb::DescriptorProto* row = msg->add_nested_type();
      row->set_name(m.name + kProtobufRowSuffix + std::to_string(level));
      Field* values = row->add_field();
      values->set_name("values");
      values->set_json_name("values");
      values->set_number(1);
      if (level + 1 < m.dims.size()) {
        values->set_type(Field::TYPE_MESSAGE);
        values->set_label(Field::LABEL_REPEATED);
        values->set_type_name(outer + "." + m.name + kProtobufRowSuffix +
                              std::to_string(level + 1));
      } else {
        SetElement(m, true, values);
      }
    }
  }
}

}  // namespace

std::string LcmProtobufDescriptorSet(const LcmTypeRegistry& registry,
                                     const LcmStruct& type) {
  // Every struct `type` uses, by package.
  std::map<std::string, std::vector<const LcmStruct*>> by_package;
  std::map<std::string, std::set<std::string>> uses;  // package -> packages
  std::set<std::string> seen{type.full_name()};
  std::vector<const LcmStruct*> todo{&type};
  for (size_t t = 0; t < todo.size(); ++t) {
    const LcmStruct& s = *todo[t];
    by_package[s.package].push_back(&s);
    for (const LcmMember& m : s.members) {
      if (IsLcmPrimitive(m.type)) continue;
      const LcmStruct* child = registry.FindByName(m.type);
      if (child == nullptr) {
        throw std::runtime_error("LCM type " + s.full_name() + ": member '" +
                                 m.name + "' has unknown type " + m.type);
      }
      if (child->package != s.package) uses[s.package].insert(child->package);
      if (seen.insert(child->full_name()).second) todo.push_back(child);
    }
  }
  const auto file_name = [](const std::string& package) {
    return (package.empty() ? std::string("lcm_types") : package) + ".proto";
  };
  // Files in dependency order: a package once all it uses are out.
  pb::FileDescriptorSet set;
  std::set<std::string> done;
  while (done.size() < by_package.size()) {
    bool progress = false;
    for (const auto& [package, structs] : by_package) {
      if (done.count(package) != 0) continue;
      const std::set<std::string>& needs = uses[package];
      bool ready = true;
      for (const std::string& p : needs) ready = ready && done.count(p) != 0;
      if (!ready) continue;
      pb::FileDescriptorProto* file = set.add_file();
      file->set_name(file_name(package));
      if (!package.empty()) file->set_package(package);
      file->set_syntax("proto3");
      for (const std::string& p : needs) file->add_dependency(file_name(p));
      for (const LcmStruct* s : structs) AddMessage(*s, file);
      done.insert(package);
      progress = true;
    }
    if (!progress) {
      throw std::runtime_error("LCM type " + type.full_name() +
                               ": its packages use each other in a circle, "
                               "which protobuf files cannot");
    }
  }
  return set.SerializeAsString();
}

}  // namespace mrsim
