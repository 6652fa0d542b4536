#pragma once
#include <string>

namespace dampbench::sweep {

/// Exclusive use of a store by one `dampbench run`: an flock on "<store>.lock", released when the process ends
/// (even by SIGKILL), so a second run on the same store is refused at once instead of both writing it.
class StoreLock {
 public:
  /// Creates the store's folder if needed and takes the lock; StoreError naming the store when another process
  /// holds it or the lock file cannot be created.
  explicit StoreLock(const std::string& store_path);
  StoreLock(const StoreLock&) = delete;
  StoreLock& operator=(const StoreLock&) = delete;
  ~StoreLock();

 private:
  int fd_ = -1;
};

}  // namespace dampbench::sweep
