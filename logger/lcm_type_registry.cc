#include "logger/lcm_type_registry.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "logger/embedded_lcm_types.h"

namespace mrsim {
namespace {

struct Token {
  std::string text;
  int line = 0;
};

std::vector<Token> Tokenize(const std::string& text,
                            const std::string& source_name) {
  std::vector<Token> tokens;
  int line = 1;
  size_t i = 0;
  const size_t n = text.size();
  while (i < n) {
    const char c = text[i];
    if (c == '\n') {
      ++line;
      ++i;
    } else if (std::isspace(static_cast<unsigned char>(c))) {
      ++i;
    } else if (c == '/' && i + 1 < n && text[i + 1] == '/') {
      while (i < n && text[i] != '\n') ++i;
    } else if (c == '/' && i + 1 < n && text[i + 1] == '*') {
      const size_t end = text.find("*/", i + 2);
      if (end == std::string::npos) {
        throw std::runtime_error(source_name + ":" + std::to_string(line) +
                                 ": unterminated /* comment");
      }
      line += static_cast<int>(
          std::count(text.begin() + i, text.begin() + end, '\n'));
      i = end + 2;
    } else if (std::isalnum(static_cast<unsigned char>(c)) || c == '_' ||
               c == '.' || c == '-' || c == '+') {
      size_t j = i;
      while (j < n && (std::isalnum(static_cast<unsigned char>(text[j])) ||
                       text[j] == '_' || text[j] == '.' || text[j] == '-' ||
                       text[j] == '+')) {
        ++j;
      }
      tokens.push_back({text.substr(i, j - i), line});
      i = j;
    } else if (std::string(";{}[]=,").find(c) != std::string::npos) {
      tokens.push_back({std::string(1, c), line});
      ++i;
    } else {
      throw std::runtime_error(source_name + ":" + std::to_string(line) +
                               ": unexpected character '" + std::string(1, c) +
                               "'");
    }
  }
  return tokens;
}

class Parser {
 public:
  Parser(std::vector<Token> tokens, std::string source_name)
      : tokens_(std::move(tokens)), source_(std::move(source_name)) {}

  std::vector<LcmStruct> Parse() {
    std::vector<LcmStruct> out;
    std::string package;
    while (!AtEnd()) {
      const std::string word = Next("'package' or 'struct'");
      if (word == "package") {
        package = Next("a package name");
        Expect(";");
      } else if (word == "struct") {
        out.push_back(ParseStruct(package));
      } else {
        Fail("expected 'package' or 'struct', found '" + word + "'");
      }
    }
    return out;
  }

 private:
  LcmStruct ParseStruct(const std::string& package) {
    LcmStruct s;
    s.package = package;
    s.name = Next("a struct name");
    Expect("{");
    while (Peek() != "}") {
      const std::string type = Next("a member type or '}'");
      if (type == "const") {
        Next("a constant type");
        do {
          Next("a constant name");
          Expect("=");
          Next("a constant value");
        } while (Accept(","));
        Expect(";");
        continue;
      }
      LcmMember m;
      m.type = type;
      if (!IsLcmPrimitive(type) && type.find('.') == std::string::npos &&
          !package.empty()) {
        m.type = package + "." + type;
      }
      m.name = Next("a member name");
      while (Accept("[")) {
        LcmDimension d;
        d.size = Next("an array size");
        d.variable = !std::isdigit(static_cast<unsigned char>(d.size[0]));
        if (d.variable && std::none_of(s.members.begin(), s.members.end(),
                                       [&](const LcmMember& prev) {
                                         return prev.name == d.size &&
                                                prev.dims.empty();
                                       })) {
          Fail("array size '" + d.size + "' of member '" + m.name +
               "' is not an earlier scalar member of " + s.name);
        }
        m.dims.push_back(d);
        Expect("]");
      }
      Expect(";");
      s.members.push_back(std::move(m));
    }
    Expect("}");
    return s;
  }

  bool AtEnd() const { return pos_ >= tokens_.size(); }
  std::string Peek() const { return AtEnd() ? "" : tokens_[pos_].text; }
  std::string Next(const std::string& what) {
    if (AtEnd()) Fail("expected " + what + ", found end of file");
    return tokens_[pos_++].text;
  }
  bool Accept(const std::string& t) {
    if (Peek() != t) return false;
    ++pos_;
    return true;
  }
  void Expect(const std::string& t) {
    if (!Accept(t)) {
      Fail("expected '" + t + "', found '" +
           (AtEnd() ? std::string("end of file") : Peek()) + "'");
    }
  }
  [[noreturn]] void Fail(const std::string& msg) const {
    const int line = tokens_.empty() ? 1
                     : AtEnd()       ? tokens_.back().line
                                     : tokens_[pos_].line;
    throw std::runtime_error(source_ + ":" + std::to_string(line) + ": " + msg);
  }

  std::vector<Token> tokens_;
  std::string source_;
  size_t pos_ = 0;
};

// lcm-gen's hash steps (lcmgen.c): a char-wise rotate-and-add.
int64_t HashUpdate(int64_t v, char c) {
  const uint64_t u = static_cast<uint64_t>(v);
  return static_cast<int64_t>(((u << 8) ^ static_cast<uint64_t>(v >> 55)) +
                              static_cast<uint64_t>(static_cast<int64_t>(c)));
}

int64_t HashString(int64_t v, const std::string& s) {
  v = HashUpdate(v, static_cast<char>(s.size()));
  for (char c : s) v = HashUpdate(v, c);
  return v;
}

int64_t BaseHash(const LcmStruct& s) {
  int64_t v = 0x12345678;
  for (const LcmMember& m : s.members) {
    v = HashString(v, m.name);
    if (IsLcmPrimitive(m.type)) v = HashString(v, m.type);
    v = HashUpdate(v, static_cast<char>(m.dims.size()));
    for (const LcmDimension& d : m.dims) {
      v = HashUpdate(v, static_cast<char>(d.variable ? 1 : 0));
      v = HashString(v, d.size);
    }
  }
  return v;
}

}  // namespace

bool IsLcmPrimitive(const std::string& type) {
  static const char* const kPrimitives[] = {"int8_t",  "int16_t", "int32_t",
                                            "int64_t", "byte",    "boolean",
                                            "float",   "double",  "string"};
  return std::find(std::begin(kPrimitives), std::end(kPrimitives), type) !=
         std::end(kPrimitives);
}

std::vector<LcmStruct> ParseLcmDefinitions(const std::string& text,
                                           const std::string& source_name) {
  return Parser(Tokenize(text, source_name), source_name).Parse();
}

void LcmTypeRegistry::AddDefinitions(const std::string& text,
                                     const std::string& source_name) {
  for (LcmStruct& s : ParseLcmDefinitions(text, source_name)) {
    by_name_[s.full_name()] = std::move(s);
  }
  Reindex();
}

void LcmTypeRegistry::AddPath(const std::string& path) {
  namespace fs = std::filesystem;
  std::vector<fs::path> files;
  std::error_code ec;
  if (fs::is_directory(path, ec)) {
    for (const auto& entry : fs::directory_iterator(path, ec)) {
      if (entry.path().extension() == ".lcm") files.push_back(entry.path());
    }
    std::sort(files.begin(), files.end());
  } else {
    files.push_back(path);
  }
  for (const fs::path& f : files) {
    std::ifstream in(f);
    if (!in)
      throw std::runtime_error("cannot read LCM type file " + f.string());
    std::stringstream ss;
    ss << in.rdbuf();
    AddDefinitions(ss.str(), f.string());
  }
}

LcmTypeRegistry LcmTypeRegistry::WithBuiltinTypes() {
  LcmTypeRegistry registry;
  for (const EmbeddedLcmSource& src : EmbeddedLcmSources()) {
    try {
      for (LcmStruct& s : ParseLcmDefinitions(src.text, src.name)) {
        registry.by_name_[s.full_name()] = std::move(s);
      }
    } catch (const std::runtime_error& e) {
      registry.warnings_.push_back(std::string(e.what()) +
                                   " (its types are not decoded)");
    }
  }
  registry.Reindex();
  for (const auto& entry : registry.by_name_) {
    // Not a structured binding: C++17 lambdas cannot capture one (clang).
    const std::string& name = entry.first;
    if (std::none_of(registry.by_hash_.begin(), registry.by_hash_.end(),
                     [&](const auto& h) { return h.second == name; })) {
      registry.warnings_.push_back("LCM type " + name +
                                   " uses a type that is not defined (its "
                                   "messages are not decoded)");
    }
  }
  return registry;
}

const LcmStruct* LcmTypeRegistry::FindByHash(int64_t hash) const {
  auto it = by_hash_.find(hash);
  return it == by_hash_.end() ? nullptr : FindByName(it->second);
}

const LcmStruct* LcmTypeRegistry::FindByName(
    const std::string& full_name) const {
  auto it = by_name_.find(full_name);
  return it == by_name_.end() ? nullptr : &it->second;
}

int64_t LcmTypeRegistry::Fingerprint(const LcmStruct& s) const {
  std::vector<const LcmStruct*> parents;
  return static_cast<int64_t>(ComputeHash(s, &parents));
}

std::vector<const LcmStruct*> LcmTypeRegistry::structs() const {
  std::vector<const LcmStruct*> out;
  for (const auto& [name, s] : by_name_) out.push_back(&s);
  return out;
}

// The recursive part lcm-gen emits as _computeHash: member types are added
// in, a type already on the path counts 0, and the sum is rotated left by 1.
uint64_t LcmTypeRegistry::ComputeHash(
    const LcmStruct& s, std::vector<const LcmStruct*>* parents) const {
  if (std::find(parents->begin(), parents->end(), &s) != parents->end()) {
    return 0;
  }
  parents->push_back(&s);
  uint64_t hash = static_cast<uint64_t>(BaseHash(s));
  for (const LcmMember& m : s.members) {
    if (IsLcmPrimitive(m.type)) continue;
    const LcmStruct* child = FindByName(m.type);
    if (child == nullptr) {
      parents->pop_back();
      throw std::runtime_error("LCM type " + s.full_name() + ": member '" +
                               m.name + "' has unknown type " + m.type);
    }
    hash += ComputeHash(*child, parents);
  }
  parents->pop_back();
  return (hash << 1) + ((hash >> 63) & 1);
}

void LcmTypeRegistry::Reindex() {
  by_hash_.clear();
  for (const auto& [name, s] : by_name_) {
    try {
      by_hash_[Fingerprint(s)] = name;
    } catch (const std::runtime_error&) {
      // A struct that uses a type we do not have cannot be decoded; leave it
      // out so its messages count as unknown.
    }
  }
}

}  // namespace mrsim
