// Message types read from their .lcm definitions, so the logger can identify
// a message by its fingerprint and decode it without generated code.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace mrsim {

// One array dimension: a constant size ("3") or the name of an earlier
// integer member of the same struct ("num_modules").
struct LcmDimension {
  bool variable = false;
  std::string size;
};

// One member of a struct; `type` is a primitive name (int8_t, int16_t,
// int32_t, int64_t, byte, boolean, float, double, string) or a struct name,
// qualified with its package ("mrsim.pose_t").
struct LcmMember {
  std::string name;
  std::string type;
  std::vector<LcmDimension> dims;
};

// One struct of an .lcm file.
struct LcmStruct {
  std::string package;
  std::string name;  // short name, e.g. "robot_state_t"
  std::vector<LcmMember> members;
  std::string full_name() const {
    return package.empty() ? name : package + "." + name;
  }
};

bool IsLcmPrimitive(const std::string& type);

// Parses the text of one .lcm file. Throws std::runtime_error naming
// `source_name`, the line and what was expected.
std::vector<LcmStruct> ParseLcmDefinitions(const std::string& text,
                                           const std::string& source_name);

// Every known struct with its fingerprint (the 64-bit hash lcm-gen puts in
// front of each encoded message).
class LcmTypeRegistry {
 public:
  // Adds the structs of one .lcm file (see ParseLcmDefinitions).
  void AddDefinitions(const std::string& text, const std::string& source_name);
  // Adds a .lcm file, or every .lcm file of a folder. Throws naming the path.
  void AddPath(const std::string& path);
  // The types generated from lcmtypes/mrsim/*.lcm at build time. A file
  // that does not parse is left out and named in warnings(), so one new
  // definition cannot stop the logger.
  static LcmTypeRegistry WithBuiltinTypes();
  const std::vector<std::string>& warnings() const { return warnings_; }

  // The struct whose fingerprint is `hash`, or nullptr.
  const LcmStruct* FindByHash(int64_t hash) const;
  // A struct by full name ("mrsim.pose_t"), or nullptr.
  const LcmStruct* FindByName(const std::string& full_name) const;
  // The fingerprint of a struct known to the registry. Throws when a member
  // names a type the registry does not hold.
  int64_t Fingerprint(const LcmStruct& s) const;
  std::vector<const LcmStruct*> structs() const;

 private:
  uint64_t ComputeHash(const LcmStruct& s,
                       std::vector<const LcmStruct*>* parents) const;
  void Reindex();

  std::map<std::string, LcmStruct> by_name_;
  std::map<int64_t, std::string> by_hash_;
  std::vector<std::string> warnings_;
};

}  // namespace mrsim
