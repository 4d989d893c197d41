#include "command_runner.hpp"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "test_data.hpp"

extern char** environ;

namespace posekit::testing {
namespace {

std::string read_file(const std::filesystem::path& file) {
  std::ifstream stream(file, std::ios::binary);
  std::ostringstream text;
  text << stream.rdbuf();
  return text.str();
}

}  // namespace

std::vector<std::string> CommandResult::err_lines() const {
  std::vector<std::string> lines;
  std::istringstream stream(err);
  std::string line;
  while (std::getline(stream, line)) lines.push_back(line);
  return lines;
}

namespace {

CommandResult run_until(const std::string& program, const std::vector<std::string>& arguments,
                        const std::function<bool()>& stop) {
  TemporaryDirectory capture;
  const std::string out_path = (capture.path() / "stdout").string();
  const std::string err_path = (capture.path() / "stderr").string();

  std::vector<std::string> argv_storage{program};
  argv_storage.insert(argv_storage.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (std::string& argument : argv_storage) argv.push_back(argument.data());
  argv.push_back(nullptr);

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t child = 0;
  const int spawn_error = posix_spawnp(&child, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawn_error != 0) throw std::runtime_error("cannot start " + program);

  int wait_status = 0;
  if (stop) {
    // Polls the condition while the child runs; kills it the first time the condition holds.
    while (waitpid(child, &wait_status, WNOHANG) == 0) {
      if (stop()) {
        kill(child, SIGKILL);
        waitpid(child, &wait_status, 0);
        break;
      }
      usleep(2000);
    }
  } else {
    waitpid(child, &wait_status, 0);
  }
  CommandResult result;
  if (WIFEXITED(wait_status)) {
    result.exit_status = WEXITSTATUS(wait_status);
  } else if (WIFSIGNALED(wait_status)) {
    result.exit_status = 128 + WTERMSIG(wait_status);
  }
  result.out = read_file(out_path);
  result.err = read_file(err_path);
  return result;
}

}  // namespace

CommandResult run_posekit(const std::vector<std::string>& arguments) { return run_until(POSEKIT_CLI_PATH, arguments, {}); }

CommandResult run_posekit_until(const std::vector<std::string>& arguments, const std::function<bool()>& stop) {
  return run_until(POSEKIT_CLI_PATH, arguments, stop);
}

CommandResult run_program(const std::string& program, const std::vector<std::string>& arguments) {
  return run_until(program, arguments, {});
}

}  // namespace posekit::testing
