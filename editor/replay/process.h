// Child processes without a shell (argv, posix_spawnp: paths need no quoting), stdin from /dev/null, stdout and
// stderr into one file: ffmpeg for the recorder's MP4, sbatch / squeue / scancel and the local pool of the farm.
#pragma once

#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

namespace trispline::editor {

// Starts argv[0] (a path, or a name looked up on PATH) with `argv`, its output into `output` (truncated) and the
// environment `env` ("NAME=value" strings; the parent's when null). Returns the process id. Throws
// std::runtime_error naming the program when it cannot be started.
pid_t start_process(const std::vector<std::string>& argv, const std::filesystem::path& output,
                    const std::vector<std::string>* env = nullptr);

// The exit status of a waitpid() status: 0–255, or −1 when the process died of a signal.
int exit_status(int wait_status);

// Waits for `pid` (retrying on EINTR); its exit status, −1 when it died of a signal or cannot be waited for.
int wait_process(pid_t pid);

// start_process + wait_process; −1 when it could not start.
int run_process(const std::vector<std::string>& argv, const std::filesystem::path& output);

// What a program printed (stdout and stderr, through a temporary file) and its exit status (−1: did not run).
struct ProcessOutput {
  int status = -1;
  std::string text;
};
ProcessOutput run_process_output(const std::vector<std::string>& argv);

}  // namespace trispline::editor
