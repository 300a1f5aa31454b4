#pragma once
// Test support: the real program (GEOHYBRID_EXECUTABLE) run in a child process, so that a test
// meets what a user meets: its exit status, its messages and the files it leaves. Used by the
// interrupt tests (a real signal) and the full-disk tests (a real failed write).
#include "file_size_limit.h"

#include <gtest/gtest.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

extern char **environ;

namespace geohybrid::testing
{
/// `geohybrid ARGS...` started in a child process, its stdout and stderr in `log`. The child gets
/// this process's environment without the MPI launcher's variables (this test program is an MPI
/// process itself; the child is a fresh singleton), with `extra_environment` ("NAME=value") added.
inline pid_t start_geohybrid(const std::vector<std::string> &arguments, const std::filesystem::path &log,
                             const std::vector<std::string> &extra_environment = {})
{
  std::vector<std::string> words{GEOHYBRID_EXECUTABLE};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char *> argv;
  for (std::string &w : words)
    argv.push_back(w.data());
  argv.push_back(nullptr);
  std::vector<std::string> variables;
  for (char **v = environ; *v; ++v)
    {
      const std::string variable = *v;
      bool launcher = false;
      for (const char *prefix : {"OMPI_", "PMIX_", "OPAL_", "ORTE_", "PRTE_"})
        launcher = launcher || variable.rfind(prefix, 0) == 0;
      if (!launcher)
        variables.push_back(variable);
    }
  variables.insert(variables.end(), extra_environment.begin(), extra_environment.end());
  std::vector<char *> envp;
  for (std::string &v : variables)
    envp.push_back(v.data());
  envp.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&files, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = -1;
  const int error = posix_spawn(&pid, argv[0], &files, nullptr, argv.data(), envp.data());
  posix_spawn_file_actions_destroy(&files);
  EXPECT_EQ(error, 0) << "cannot start " << argv[0] << ": " << std::strerror(error);
  return error == 0 ? pid : -1;
}

/// The child's exit status (128 + the signal if a signal killed it), or -1.
inline int wait_for(pid_t pid)
{
  int status = 0;
  if (pid <= 0 || waitpid(pid, &status, 0) != pid)
    return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : WIFSIGNALED(status) ? 128 + WTERMSIG(status) : -1;
}

inline int run_geohybrid(const std::vector<std::string> &arguments, const std::filesystem::path &log)
{
  return wait_for(start_geohybrid(arguments, log));
}

/// run_geohybrid() with every file the child writes limited to `bytes` (file_size_limit.h): a
/// write beyond fails with EFBIG, as on a full disk with ENOSPC, whatever the file. The child
/// inherits the limit and the ignored SIGXFSZ at its start; this process has them only for that
/// moment. MPI's start would meet the limit too: Open MPI's PMIx keeps its store in shared-memory
/// files of some megabytes unless told to keep it in memory (PMIX_MCA_gds=hash).
inline int run_geohybrid_with_file_size_limit(const std::vector<std::string> &arguments,
                                              const std::filesystem::path &log, std::size_t bytes)
{
  pid_t child = -1;
  {
    const FileSizeLimit limit(bytes);
    child = start_geohybrid(arguments, log, {"PMIX_MCA_gds=hash"});
  }
  return wait_for(child);
}

#ifdef GEOHYBRID_FULL_DISK_PRELOAD
/// run_geohybrid() on a disk full for the files of these base names only (`names`, separated by
/// commas; full_disk_preload.cc, preloaded into the child): each is created, and every write to it
/// fails with ENOSPC, whatever its size.
inline int run_geohybrid_with_full_files(const std::vector<std::string> &arguments, const std::filesystem::path &log,
                                         const std::string &names)
{
  return wait_for(start_geohybrid(arguments, log,
                                  {std::string("LD_PRELOAD=") + GEOHYBRID_FULL_DISK_PRELOAD,
                                   "GEOHYBRID_TEST_FULL_FILES=" + names}));
}
#endif
} // namespace geohybrid::testing
