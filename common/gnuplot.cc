#include "common/gnuplot.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <string>

namespace common {

std::string gnuplot_quote(const std::string& text) {
  std::string out = "'";
  for (char c : text) out += (c == '\'') ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string run_gnuplot(const std::string& script_path, const std::string& working_dir, const std::string& log_path) {
  const pid_t pid = fork();
  if (pid < 0) return "cannot start gnuplot for " + script_path + ": fork failed";
  if (pid == 0) {
    const int out = open(log_path.empty() ? "/dev/null" : log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out >= 0) {
      dup2(out, STDOUT_FILENO);
      dup2(out, STDERR_FILENO);
      close(out);
    }
    if (!working_dir.empty() && chdir(working_dir.c_str()) != 0) _exit(126);
    execlp("gnuplot", "gnuplot", script_path.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 0) return "";
  const std::string where = log_path.empty() ? "" : " (see " + log_path + ")";
  if (WIFEXITED(status) && WEXITSTATUS(status) == 127) return "gnuplot not found (install gnuplot-nox) for " + script_path;
  return "gnuplot failed (exit status " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ") on " +
         script_path + where;
}

}  // namespace common
