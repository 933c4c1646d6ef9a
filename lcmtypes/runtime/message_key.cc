#include "lcmtypes/runtime/message_key.h"

#include <fcntl.h>
#include <openssl/rand.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>

#include "lcmtypes/runtime/usage_error.h"

namespace mrsim {
namespace {

constexpr std::size_t kKeyBytes = 32;
constexpr std::size_t kMinKeyBytes = 16;
constexpr off_t kMaxKeyFileSize = 4096;
constexpr const char* kHeader =
    "# mrsim message key (keep it secret; docs/security.md)\n";

int HexDigit(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  if (c >= 'A' && c <= 'F') return c - 'A' + 10;
  return -1;
}

std::string Fail(const std::string& path, const std::string& what) {
  return "key file " + path + ": " + what;
}

// Closes the descriptor whatever happens.
struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) close(fd);
  }
};

}  // namespace

void WriteKeyFile(const std::string& path) {
  unsigned char key[kKeyBytes];
  if (RAND_bytes(key, sizeof key) != 1) {
    throw std::runtime_error("OpenSSL cannot draw random bytes for a key");
  }
  static const char kHex[] = "0123456789abcdef";
  std::string text = kHeader;
  for (unsigned char b : key) {
    text += kHex[b >> 4];
    text += kHex[b & 15];
  }
  text += '\n';
  Fd out{open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600)};
  if (out.fd < 0) {
    throw UsageError(Fail(path, errno == EEXIST
                                    ? "exists; remove it first (a new key "
                                      "locks out every host with the old one)"
                                    : std::strerror(errno)));
  }
  // O_CREAT's mode is masked by the umask; 0600 is what we want anyway.
  if (fchmod(out.fd, 0600) != 0 ||
      write(out.fd, text.data(), text.size()) !=
          static_cast<ssize_t>(text.size()) ||
      fsync(out.fd) != 0) {
    const std::string why = std::strerror(errno);
    unlink(path.c_str());
    throw UsageError(Fail(path, "cannot write: " + why));
  }
}

std::string ReadKeyFile(const std::string& path) {
  Fd in{open(path.c_str(), O_RDONLY | O_CLOEXEC)};
  if (in.fd < 0) throw UsageError(Fail(path, std::strerror(errno)));
  struct stat st {};
  if (fstat(in.fd, &st) != 0)
    throw UsageError(Fail(path, std::strerror(errno)));
  if (!S_ISREG(st.st_mode)) throw UsageError(Fail(path, "not a regular file"));
  if ((st.st_mode & 077) != 0) {
    char mode[8];
    std::snprintf(mode, sizeof mode, "%04o", st.st_mode & 07777);
    throw UsageError(Fail(
        path, std::string("readable or writable by group or others (mode ") +
                  mode + "); run: chmod 600 " + path));
  }
  if (st.st_size > kMaxKeyFileSize) {
    throw UsageError(Fail(path, "larger than 4096 bytes: not a key file"));
  }
  std::string text(static_cast<std::size_t>(st.st_size), '\0');
  const ssize_t got = read(in.fd, text.data(), text.size());
  if (got < 0) throw UsageError(Fail(path, std::strerror(errno)));
  text.resize(static_cast<std::size_t>(got));
  std::string key;
  std::size_t line = 1;
  bool comment = false;
  int high = -1;
  for (char c : text) {
    if (c == '\n') {
      ++line;
      comment = false;
      continue;
    }
    if (comment) continue;
    if (c == '#') {
      comment = true;
      continue;
    }
    if (c == ' ' || c == '\t' || c == '\r') continue;
    const int d = HexDigit(c);
    if (d < 0) {
      throw UsageError(Fail(path, "line " + std::to_string(line) +
                                      ": expected hexadecimal digits (write "
                                      "one with: mrsim keygen PATH)"));
    }
    if (high < 0) {
      high = d;
    } else {
      key += static_cast<char>(high * 16 + d);
      high = -1;
    }
  }
  if (high >= 0) throw UsageError(Fail(path, "an odd number of hex digits"));
  if (key.size() < kMinKeyBytes) {
    throw UsageError(Fail(path,
                          "a key needs at least 16 bytes (32 hex "
                          "digits); write one with: mrsim keygen PATH"));
  }
  return key;
}

AuthConfig LoadAuthConfig(const std::string& flag, bool accept_replays) {
  AuthConfig config;
  config.accept_replays = accept_replays;
  config.key_file = flag;
  if (config.key_file.empty()) {
    const char* env = std::getenv(kKeyFileEnv);
    if (env != nullptr) config.key_file = env;
  }
  if (!config.key_file.empty()) config.key = ReadKeyFile(config.key_file);
  return config;
}

void AuthFlags::ExportToChildren() const {
  if (key_file.empty()) return;
  std::error_code error;
  const std::filesystem::path path = std::filesystem::absolute(key_file, error);
  setenv(kKeyFileEnv, error ? key_file.c_str() : path.c_str(), 1);
}

}  // namespace mrsim
