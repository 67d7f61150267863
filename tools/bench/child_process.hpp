#pragma once
// Child processes for sweeps: another run of this program (or any executable) with its
// standard output and error going to a log file.
#include <sys/types.h>
#include <string>
#include <vector>

namespace deepnav::bench {

/// The path of the running executable (/proc/self/exe).
std::string self_executable();
/// Starts argv[0] with arguments argv[1..] (no shell), stdout and stderr appended to
/// log_path; throws InputError naming the program when it cannot start.
pid_t start_child(const std::vector<std::string>& argv, const std::string& log_path);
/// Waits for that child; returns its exit status (128 + signal when killed).
int wait_child(pid_t pid);
/// Waits for any child; returns its pid and sets status as wait_child does.
pid_t wait_any_child(int& status);
/// One shell-quoted command line for printing (GNU parallel, a Slurm array script).
std::string shell_command_line(const std::vector<std::string>& argv);

}  // namespace deepnav::bench
