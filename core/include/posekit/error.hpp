// Exceptions that posekit throws. Every message is one line a user can act on.
#pragma once

#include <stdexcept>
#include <string>

namespace posekit {

/// Base class of every posekit exception.
class Error : public std::runtime_error {
 public:
  explicit Error(const std::string& message) : std::runtime_error(message) {}
};

/// Bad input data: a file that cannot be read or a mesh that breaks a rule.
/// The message starts with "FILE:LINE: " (or "FILE: " when no line applies).
class InputError : public Error {
 public:
  InputError(const std::string& file, long line, const std::string& problem)
      : Error(format(file, line, problem)), file_(file), line_(line), problem_(problem) {}
  const std::string& file() const { return file_; }
  /// 1-based line number, or 0 when the problem has no line.
  long line() const { return line_; }
  const std::string& problem() const { return problem_; }

 private:
  static std::string format(const std::string& file, long line, const std::string& problem) {
    return line > 0 ? file + ":" + std::to_string(line) + ": " + problem : file + ": " + problem;
  }
  std::string file_;
  long line_;
  std::string problem_;
};

/// An argument outside its documented range; the message names the argument.
class ArgumentError : public Error {
 public:
  explicit ArgumentError(const std::string& message) : Error(message) {}
};

/// A compute-device API call failed; the message carries the call, file and line.
class DeviceError : public Error {
 public:
  explicit DeviceError(const std::string& message) : Error(message) {}
};

}  // namespace posekit
