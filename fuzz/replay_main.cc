// Replays fuzz inputs without libFuzzer: every file named on the command
// line, or found directly in a folder named there, is passed once to
// LLVMFuzzerTestOneInput. ctest runs this over a target's seed corpus and
// its regressions, so an input that once crashed a reader is replayed by
// every build, including the sanitizer one.
#include <sys/stat.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {

// Inputs are small by construction (libFuzzer's default -max_len is 4096);
// anything larger in the corpus folders is a mistake, not an input.
constexpr std::uintmax_t kMaxInputBytes = 64u << 20;

bool Replay(const std::filesystem::path& file) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(file, ec);
  if (ec || size > kMaxInputBytes) {
    std::fprintf(stderr, "replay: %s: unreadable or larger than %ju bytes\n",
                 file.c_str(), kMaxInputBytes);
    return false;
  }
  std::ifstream in(file, std::ios::binary);
  std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                             std::istreambuf_iterator<char>());
  LLVMFuzzerTestOneInput(bytes.data(), bytes.size());
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  int replayed = 0;
  bool ok = true;
  for (int i = 1; i < argc; ++i) {
    const std::filesystem::path arg(argv[i]);
    std::error_code ec;
    if (std::filesystem::is_directory(arg, ec)) {
      std::vector<std::filesystem::path> files;
      for (const auto& entry : std::filesystem::directory_iterator(arg)) {
        if (entry.is_regular_file()) files.push_back(entry.path());
      }
      std::sort(files.begin(), files.end());  // same order on every host
      for (const auto& file : files) {
        ok = Replay(file) && ok;
        ++replayed;
      }
    } else if (std::filesystem::exists(arg, ec)) {
      ok = Replay(arg) && ok;
      ++replayed;
    }
    // A missing folder is fine: a target may have no regressions yet.
  }
  std::printf("replayed %d inputs\n", replayed);
  if (replayed == 0) {
    std::fprintf(stderr,
                 "replay: no inputs found (a seed corpus is required)\n");
    return 1;
  }
  return ok ? 0 : 1;
}
