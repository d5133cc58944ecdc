#include "editor/replay/process.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <stdexcept>

extern char** environ;

namespace trispline::editor {

pid_t start_process(const std::vector<std::string>& argv, const std::filesystem::path& output,
                    const std::vector<std::string>* env) {
  if (argv.empty()) throw std::runtime_error("no program to start");
  std::vector<char*> args, envp;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);
  if (env) {
    for (const std::string& e : *env) envp.push_back(const_cast<char*>(e.c_str()));
    envp.push_back(nullptr);
  }
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), env ? envp.data() : environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) throw std::runtime_error("cannot start " + argv[0] + ": " + std::strerror(rc));
  return pid;
}

int exit_status(int wait_status) { return WIFEXITED(wait_status) ? WEXITSTATUS(wait_status) : -1; }

int wait_process(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return exit_status(status);
}

int run_process(const std::vector<std::string>& argv, const std::filesystem::path& output) {
  try {
    return wait_process(start_process(argv, output));
  } catch (const std::runtime_error&) {
    return -1;
  }
}

ProcessOutput run_process_output(const std::vector<std::string>& argv) {
  ProcessOutput out;
  std::string name = (std::filesystem::temp_directory_path() / "trispline-output-XXXXXX").string();
  const int fd = ::mkstemp(name.data());
  if (fd < 0) return out;
  ::close(fd);
  out.status = run_process(argv, name);
  std::ifstream in(name, std::ios::binary);
  out.text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  std::error_code ec;
  std::filesystem::remove(name, ec);
  return out;
}

}  // namespace trispline::editor
