#include "cli_runner.h"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

extern char** environ;

namespace mddual::cli_test {
namespace {

std::vector<char*> argvFor(std::vector<std::string>* args) {
  std::vector<char*> argv;
  for (std::string& a : *args) argv.push_back(a.data());
  argv.push_back(nullptr);
  return argv;
}

std::vector<std::string> withBinary(const std::vector<std::string>& args) {
  std::vector<std::string> all{cliPath()};
  all.insert(all.end(), args.begin(), args.end());
  return all;
}

int exitStatus(int status) {
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

pid_t spawn(std::vector<std::string> args, posix_spawn_file_actions_t* actions) {
  std::vector<char*> argv = argvFor(&args);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, argv[0], actions, nullptr, argv.data(), environ);
  if (rc != 0) throw std::runtime_error("posix_spawn failed for " + args[0]);
  return pid;
}

}  // namespace

const char* cliPath() {
  return MDDUAL_CLI_PATH;
}

TempDir::TempDir() {
  std::string pattern = (std::filesystem::temp_directory_path() / "mddual_cli_test_XXXXXX").string();
  if (mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  path_ = pattern;
}

TempDir::~TempDir() {
  std::error_code ignored;
  std::filesystem::remove_all(path_, ignored);
}

std::string TempDir::write(const std::string& name, const std::string& text) const {
  const std::string file = path_ + "/" + name;
  std::ofstream out(file, std::ios::binary);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + file);
  return file;
}

std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::vector<std::string> splitLines(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

CliRun runCli(const std::vector<std::string>& args, const std::string& stdin_text) {
  const TempDir dir;
  const std::string in = dir.write("stdin", stdin_text);
  const std::string out = dir.path() + "/stdout";
  const std::string err = dir.path() + "/stderr";
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 0, in.c_str(), O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 1, out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, 2, err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const pid_t pid = spawn(withBinary(args), &actions);
  posix_spawn_file_actions_destroy(&actions);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  CliRun run;
  run.exit_code = exitStatus(status);
  run.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  run.out = readFile(out);
  run.err = readFile(err);
  return run;
}

CliRun runCliWithMemoryLimit(const std::vector<std::string>& args, const std::string& stdin_text,
                             std::size_t address_space_bytes) {
  const TempDir dir;
  const std::string in = dir.write("stdin", stdin_text);
  const std::string out = dir.path() + "/stdout";
  const std::string err = dir.path() + "/stderr";
  std::vector<std::string> all = withBinary(args);
  std::vector<char*> argv = argvFor(&all);
  // posix_spawn cannot set a limit in the child: fork, limit, exec (only
  // async-signal-safe calls between fork and exec).
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    const int fd_in = open(in.c_str(), O_RDONLY);
    const int fd_out = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int fd_err = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd_in < 0 || fd_out < 0 || fd_err < 0 || dup2(fd_in, 0) < 0 || dup2(fd_out, 1) < 0 || dup2(fd_err, 2) < 0) {
      _exit(127);
    }
    rlimit limit{};
    limit.rlim_cur = address_space_bytes;
    limit.rlim_max = address_space_bytes;
    if (setrlimit(RLIMIT_AS, &limit) != 0) _exit(126);
    execv(argv[0], argv.data());
    _exit(125);
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  CliRun run;
  run.exit_code = exitStatus(status);
  run.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  run.out = readFile(out);
  run.err = readFile(err);
  return run;
}

CliProcess::CliProcess(const std::vector<std::string>& args) {
  signal(SIGPIPE, SIG_IGN);  // a child that dies early must fail the test, not kill it
  int in_pipe[2];
  int out_pipe[2];
  if (pipe(in_pipe) != 0 || pipe(out_pipe) != 0) throw std::runtime_error("pipe failed");
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, in_pipe[0], 0);
  posix_spawn_file_actions_adddup2(&actions, out_pipe[1], 1);
  posix_spawn_file_actions_addclose(&actions, in_pipe[1]);
  posix_spawn_file_actions_addclose(&actions, out_pipe[0]);
  pid_ = spawn(withBinary(args), &actions);
  posix_spawn_file_actions_destroy(&actions);
  close(in_pipe[0]);
  close(out_pipe[1]);
  to_child_ = in_pipe[1];
  from_child_ = out_pipe[0];
}

CliProcess::~CliProcess() {
  closeInput();
  if (from_child_ >= 0) close(from_child_);
  if (pid_ > 0) {
    kill(pid_, SIGKILL);
    int status = 0;
    waitpid(pid_, &status, 0);
  }
}

void CliProcess::write(const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(to_child_, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw std::runtime_error("write to the child failed");
    done += static_cast<std::size_t>(n);
  }
}

bool CliProcess::readLine(std::string* line, int timeout_ms) {
  for (;;) {
    const std::size_t newline = buffer_.find('\n');
    if (newline != std::string::npos) {
      *line = buffer_.substr(0, newline);
      buffer_.erase(0, newline + 1);
      return true;
    }
    pollfd fd{from_child_, POLLIN, 0};
    if (poll(&fd, 1, timeout_ms) <= 0) return false;
    char chunk[4096];
    const ssize_t n = read(from_child_, chunk, sizeof(chunk));
    if (n <= 0) return false;
    buffer_.append(chunk, static_cast<std::size_t>(n));
  }
}

void CliProcess::closeInput() {
  if (to_child_ >= 0) close(to_child_);
  to_child_ = -1;
}

int CliProcess::wait() {
  int status = 0;
  while (waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
  }
  pid_ = -1;
  return exitStatus(status);
}

}  // namespace mddual::cli_test
