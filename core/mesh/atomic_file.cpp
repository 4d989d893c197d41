#include <posekit/atomic_file.hpp>

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <random>
#include <string>
#include <system_error>

#include "posekit/error.hpp"

namespace posekit {
namespace {

std::string describe_errno(int error) { return std::generic_category().message(error); }

// Removes the temporary file unless the rename has consumed it.
class TemporaryFile {
 public:
  TemporaryFile(std::filesystem::path path, int descriptor) : path_(std::move(path)), descriptor_(descriptor) {}
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  TemporaryFile(TemporaryFile&&) = delete;
  TemporaryFile& operator=(TemporaryFile&&) = delete;
  ~TemporaryFile() {
    close();
    if (!committed_) ::unlink(path_.c_str());
  }
  int descriptor() const { return descriptor_; }
  const std::filesystem::path& path() const { return path_; }
  int close() {
    if (descriptor_ < 0) return 0;
    const int result = ::close(descriptor_);
    descriptor_ = -1;
    return result;
  }
  void commit() { committed_ = true; }

 private:
  std::filesystem::path path_;
  int descriptor_;
  bool committed_ = false;
};

TemporaryFile create_temporary_beside(const std::filesystem::path& target) {
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path folder = target.has_parent_path() ? target.parent_path() : std::filesystem::path(".");
  std::random_device random;
  for (int attempt = 0; attempt < 100; ++attempt) {
    // A hidden name that no other writer picks: process id, a counter and a random number.
    const std::string name = "." + target.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                             std::to_string(counter++) + "-" + std::to_string(random() % 1000000);
    std::filesystem::path path = folder / name;
    // 0666 lets the umask decide the permissions, as for any file the user creates.
    const int descriptor = ::open(path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (descriptor >= 0) return TemporaryFile(std::move(path), descriptor);
    if (errno != EEXIST) {
      throw InputError(target.string(), 0,
                       "cannot create a file in folder '" + folder.string() + "': " + describe_errno(errno));
    }
  }
  throw InputError(target.string(), 0, "cannot create a temporary file in folder '" + folder.string() + "'");
}

}  // namespace

void write_file_atomically(const std::filesystem::path& target, std::string_view bytes) {
  const std::string name = target.string();
  TemporaryFile temporary = create_temporary_beside(target);
  const char* data = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t written = ::write(temporary.descriptor(), data, left);
    if (written < 0 && errno == EINTR) continue;
    if (written <= 0) throw InputError(name, 0, "cannot write the file: " + describe_errno(errno));
    data += written;
    left -= static_cast<std::size_t>(written);
  }
  if (::fsync(temporary.descriptor()) != 0)
    throw InputError(name, 0, "cannot write the file: " + describe_errno(errno));
  if (temporary.close() != 0) throw InputError(name, 0, "cannot write the file: " + describe_errno(errno));
  if (std::rename(temporary.path().c_str(), target.c_str()) != 0) {
    throw InputError(name, 0, "cannot replace the file: " + describe_errno(errno));
  }
  temporary.commit();
}

}  // namespace posekit
