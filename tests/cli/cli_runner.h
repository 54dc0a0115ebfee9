// Runs the built `mddual` binary for the CLI tests: with files for its
// standard streams (runCli) or with pipes, to watch it stream (CliProcess).
#pragma once

#include <sys/types.h>

#include <cstddef>
#include <string>
#include <vector>

namespace mddual::cli_test {

/// Path of the binary under test (compile definition MDDUAL_CLI_PATH).
const char* cliPath();

/// A temporary directory, removed with its contents on destruction.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::string& path() const { return path_; }
  /// Writes `text` to path()/name and returns the file's path.
  std::string write(const std::string& name, const std::string& text) const;

 private:
  std::string path_;
};

std::string readFile(const std::string& path);
/// The lines of `text` (without the newlines; a final newline ends the last line).
std::vector<std::string> splitLines(const std::string& text);
/// The number of newline characters in `text`.
inline int countLines(const std::string& text) {
  int n = 0;
  for (char c : text) n += c == '\n' ? 1 : 0;
  return n;
}

struct CliRun {
  int exit_code = -1;  ///< the process's exit status, or -1 if it did not exit normally
  int signal = 0;      ///< the signal that killed it, if any
  std::string out;
  std::string err;
};

/// Runs `mddual args...` with `stdin_text` on standard input, to completion.
CliRun runCli(const std::vector<std::string>& args, const std::string& stdin_text = "");

/// runCli with the child's address space limited to `address_space_bytes`
/// (setrlimit RLIMIT_AS), so that an allocation beyond it fails.
CliRun runCliWithMemoryLimit(const std::vector<std::string>& args, const std::string& stdin_text,
                             std::size_t address_space_bytes);

/// `mddual args...` with pipes to its standard input and output.
class CliProcess {
 public:
  explicit CliProcess(const std::vector<std::string>& args);
  ~CliProcess();
  CliProcess(const CliProcess&) = delete;
  CliProcess& operator=(const CliProcess&) = delete;

  void write(const std::string& text);
  /// One line of output (without the newline); false if none came within
  /// `timeout_ms` or the output ended.
  bool readLine(std::string* line, int timeout_ms);
  void closeInput();
  /// Waits for the process; returns its exit status (-1 if killed).
  int wait();

 private:
  pid_t pid_ = -1;
  int to_child_ = -1;
  int from_child_ = -1;
  std::string buffer_;
};

}  // namespace mddual::cli_test
