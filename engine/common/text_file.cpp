#include "engine/common/text_file.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <string>

#include "engine/common/error.hpp"

namespace dampbench {

void write_text_file(const std::string& path, const std::string& text) {
  const std::string temporary = path + ".tmp-" + std::to_string(::getpid());
  auto fail = [&](const std::string& what, int error) {
    std::remove(temporary.c_str());
    throw StoreError("cannot write '" + path + "': " + what + ": " + std::strerror(error));
  };
  std::FILE* f = std::fopen(temporary.c_str(), "wb");
  if (!f) fail("cannot create a file in its folder", errno);
  const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size() && std::fflush(f) == 0;
  const int write_error = errno;
  if (std::fclose(f) != 0 || !written) fail("writing failed", written ? errno : write_error);
  if (std::rename(temporary.c_str(), path.c_str()) != 0) fail("cannot replace it", errno);
}

}  // namespace dampbench
