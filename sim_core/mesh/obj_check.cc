#include "sim_core/mesh/obj_check.h"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace mrsim {
namespace {

std::vector<std::string_view> Tokens(std::string_view line) {
  std::vector<std::string_view> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > start) out.push_back(line.substr(start, i - start));
  }
  return out;
}

bool FiniteNumber(std::string_view token) {
  if (token.empty() || token.size() > 64) return false;
  const std::string text(token);
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && errno == 0 && std::isfinite(v);
}

// An index as OBJ writes it: 1-based, or negative counting back.
bool Index(std::string_view token, int64_t* out) {
  if (token.empty() || token.size() > 12) return false;
  size_t i = token[0] == '-' ? 1 : 0;
  if (i == token.size()) return false;
  int64_t v = 0;
  for (; i < token.size(); ++i) {
    if (token[i] < '0' || token[i] > '9') return false;
    v = v * 10 + (token[i] - '0');
  }
  *out = token[0] == '-' ? -v : v;
  return true;
}

std::string_view StripCr(std::string_view line) {
  if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
  return line;
}

struct Counts {
  int64_t v = 0, vt = 0, vn = 0;
};

}  // namespace

void CheckObjText(const char* data, std::size_t size) {
  const std::string_view text(data, size);
  // Faces may name vertices defined later (positive indices count in the
  // whole file), so the counts come first.
  Counts total;
  for (size_t at = 0; at < text.size();) {
    size_t end = text.find('\n', at);
    if (end == std::string_view::npos) end = text.size();
    const std::vector<std::string_view> t =
        Tokens(StripCr(text.substr(at, end - at)));
    at = end + 1;
    if (t.empty()) continue;
    if (t[0] == "v") ++total.v;
    if (t[0] == "vt") ++total.vt;
    if (t[0] == "vn") ++total.vn;
  }
  Counts sofar;
  int64_t faces = 0;
  int line_number = 0;
  for (size_t at = 0; at < text.size();) {
    size_t end = text.find('\n', at);
    if (end == std::string_view::npos) end = text.size();
    std::string_view line = text.substr(at, end - at);
    at = end + 1;
    ++line_number;
    line = StripCr(line);
    const auto fail = [&](const std::string& what) {
      throw std::runtime_error(fmt::format("line {}: {}", line_number, what));
    };
    for (char c : line) {
      if (c == '\0') fail("a NUL byte (not an OBJ text file)");
    }
    const std::vector<std::string_view> t = Tokens(line);
    if (t.empty() || t[0][0] == '#') continue;
    const std::string_view kind = t[0];
    const auto numbers = [&](size_t least, size_t most) {
      if (t.size() - 1 < least || t.size() - 1 > most) {
        fail(fmt::format("'{}' needs {} to {} numbers", kind, least, most));
      }
      for (size_t k = 1; k < t.size(); ++k) {
        if (!FiniteNumber(t[k]))
          fail(fmt::format("'{}' is not a number", t[k]));
      }
    };
    if (kind == "v") {
      numbers(3, 7);
      ++sofar.v;
    } else if (kind == "vt") {
      numbers(1, 3);
      ++sofar.vt;
    } else if (kind == "vn") {
      numbers(3, 3);
      ++sofar.vn;
    } else if (kind == "f") {
      if (t.size() < 4) fail("a face needs at least three corners");
      for (size_t k = 1; k < t.size(); ++k) {
        std::string_view corner = t[k];
        const int64_t have[3] = {total.v, total.vt, total.vn};
        const int64_t before[3] = {sofar.v, sofar.vt, sofar.vn};
        const char* names[3] = {"vertex", "texture coordinate", "normal"};
        bool named_normal = false;
        for (int part = 0; part < 3 && !corner.empty(); ++part) {
          const size_t slash = corner.find('/');
          const std::string_view field = corner.substr(0, slash);
          corner = slash == std::string_view::npos ? std::string_view()
                                                   : corner.substr(slash + 1);
          if (field.empty() && part > 0) continue;  // v//vn
          int64_t i = 0;
          if (!Index(field, &i) || i == 0) {
            fail(fmt::format("face corner '{}': expected a non-zero index",
                             t[k]));
          }
          // Negative indices count back from the last one defined so far.
          const bool ok = i > 0 ? i <= have[part] : -i <= before[part];
          if (!ok) {
            fail(fmt::format("face corner '{}': no {} {} (the file has {})",
                             t[k], names[part], i, have[part]));
          }
          if (part == 2) named_normal = true;
        }
        // MuJoCo 2.2 reads a normal for every corner once the file has
        // any (a corner without one read past its buffers).
        if (total.vn > 0 && !named_normal) {
          fail(
              fmt::format("face corner '{}': the file has normals (vn), so "
                          "every corner must name one (v//vn or v/vt/vn)",
                          t[k]));
        }
        if (!corner.empty()) {
          fail(
              fmt::format("face corner '{}': expected v, v/vt, v//vn or "
                          "v/vt/vn",
                          t[k]));
        }
      }
      ++faces;
    } else if (kind == "o" || kind == "g" || kind == "s" || kind == "usemtl") {
      continue;
    } else {
      fail(
          fmt::format("'{}' is not an OBJ statement this reader takes (v, "
                      "vt, vn, f, o, g, s, usemtl)",
                      kind.substr(0, 32)));
    }
  }
  if (faces == 0) throw std::runtime_error("no faces (f lines)");
}

}  // namespace mrsim
