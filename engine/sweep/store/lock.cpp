#include "engine/sweep/store/lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "engine/common/error.hpp"

namespace dampbench::sweep {

StoreLock::StoreLock(const std::string& store_path) {
  const std::string lock_path = store_path + ".lock";
  std::error_code ec;
  if (const auto dir = std::filesystem::path(store_path).parent_path(); !dir.empty()) {
    std::filesystem::create_directories(dir, ec);
    if (ec) throw StoreError(fmt::format("cannot create the folder '{}' of store '{}': {}", dir.string(), store_path, ec.message()));
  }
  fd_ = ::open(lock_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw StoreError(fmt::format("cannot create the lock file '{}' of store '{}': {}", lock_path, store_path, std::strerror(errno)));
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int error = errno;
    ::close(fd_);
    fd_ = -1;
    if (error == EWOULDBLOCK)
      throw StoreError(fmt::format("store '{}' is in use by another dampbench run (it holds '{}'): wait for it to "
                                   "finish, or give this run another --store",
                                   store_path, lock_path));
    throw StoreError(fmt::format("cannot lock store '{}' ({}): {}", store_path, lock_path, std::strerror(error)));
  }
}

StoreLock::~StoreLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the flock
}

}  // namespace dampbench::sweep
