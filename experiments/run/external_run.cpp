#include "experiments/run/external_run.hpp"

#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <optional>
#include <string_view>
#include <vector>

#include "core/atomic_file.hpp"
#include "core/json_input.hpp"
#include "core/printable.hpp"
#include "envs/env.hpp"
#include "envs/scenario_descriptor.hpp"
#include "experiments/run/record.hpp"

namespace rapid {

namespace {
namespace fs = std::filesystem;

nlohmann::json job_document(const JobSpec& spec, const ExternalMethod& method, const std::string& profile,
                            const std::string& hash) {
  nlohmann::json job = {{"schema", kJobSchema},
                        {"scenario", spec.scenario},
                        {"profile", profile},
                        {"algo", spec.algo},
                        {"seed", spec.seed},
                        {"dataset", spec.dataset.empty() ? nlohmann::json(nullptr) : nlohmann::json(spec.dataset)},
                        {"dataset_path", spec.dataset_path.empty() ? nlohmann::json(nullptr)
                                                                   : nlohmann::json(fs::absolute(spec.dataset_path).string())},
                        {"config", spec.config},
                        {"method_config", method.config},
                        {"script", method.script_path},
                        {"command", method.command},
                        {"out", fs::absolute(spec.out_dir).string()},
                        {"config_hash", hash},
                        {"scenario_file", nullptr}};
  if (is_driving_scenario(spec.scenario) && !is_builtin_scenario(spec.scenario))
    job["scenario_file"] = scenario_descriptor(spec.scenario)->file;
  return job;
}

struct CommandResult {
  int exit_code = 0;
  int signal = 0;
  std::string last_stderr_line;
};

// The last non-empty line of what has been read so far.
void keep_last_line(std::string& pending, std::string& last) {
  std::size_t start = 0;
  for (std::size_t nl; (nl = pending.find('\n', start)) != std::string::npos; start = nl + 1)
    if (nl > start) last = pending.substr(start, nl - start);
  pending.erase(0, start);
  if (pending.size() > 4096) pending.erase(0, pending.size() - 4096);  // a line is shown, not kept whole
}

// The folder of the rapid_harness package this binary was built with (the build folder: the
// package and the binary are built side by side), or "" when it is not there. An external command
// is a job in its own folder, so a relative PYTHONPATH=build would not find it (issue #67).
std::string module_folder() {
  std::error_code ec;
  const fs::path binary = fs::read_symlink("/proc/self/exe", ec);
  if (ec) return "";
  return fs::is_regular_file(binary.parent_path() / "rapid_harness" / "__init__.py", ec) ? binary.parent_path().string()
                                                                                         : "";
}

// PYTHONPATH for the command: the module's folder first, then what the caller had.
std::string python_path_for_command() {
  const std::string module = module_folder();
  const char* had = std::getenv("PYTHONPATH");
  const std::string before = had != nullptr ? had : "";
  if (module.empty()) return before;
  return before.empty() ? module : module + ":" + before;
}

CommandResult run_command(std::vector<std::string> argv) {
  CommandResult result;
  // The command's environment, built before fork (the child may only exec): this process's, with
  // PYTHONPATH naming the module's folder first.
  std::vector<std::string> environment;
  for (char** e = environ; *e != nullptr; ++e)
    if (std::string_view(*e).rfind("PYTHONPATH=", 0) != 0) environment.emplace_back(*e);
  if (const std::string python_path = python_path_for_command(); !python_path.empty())
    environment.push_back("PYTHONPATH=" + python_path);
  std::vector<char*> envp;
  for (std::string& e : environment) envp.push_back(e.data());
  envp.push_back(nullptr);
  int pipe_fds[2];
  if (::pipe(pipe_fds) != 0) throw std::runtime_error(std::string("pipe: ") + std::strerror(errno));
  std::vector<char*> args;
  for (std::string& a : argv) args.push_back(a.data());
  args.push_back(nullptr);
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error(std::string("fork: ") + std::strerror(errno));
  if (pid == 0) {
    // The method dies with this process: a --job-timeout or an interrupted sweep stops both.
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(127);
    ::dup2(pipe_fds[1], STDERR_FILENO);
    ::close(pipe_fds[0]);
    ::close(pipe_fds[1]);
    ::execvpe(args[0], args.data(), envp.data());
    const std::string message = std::string("cannot start '") + args[0] + "': " + std::strerror(errno) + "\n";
    [[maybe_unused]] const auto n = ::write(STDERR_FILENO, message.data(), message.size());
    ::_exit(127);
  }
  ::close(pipe_fds[1]);
  std::string pending;
  char buffer[4096];
  for (;;) {
    const ssize_t n = ::read(pipe_fds[0], buffer, sizeof buffer);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) break;
    std::cerr.write(buffer, n);
    pending.append(buffer, static_cast<std::size_t>(n));
    keep_last_line(pending, result.last_stderr_line);
  }
  std::cerr.flush();
  if (!pending.empty()) result.last_stderr_line = pending;
  ::close(pipe_fds[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) throw std::runtime_error(std::string("waitpid: ") + std::strerror(errno));
  if (WIFSIGNALED(status)) result.signal = WTERMSIG(status);
  else result.exit_code = WEXITSTATUS(status);
  return result;
}

// What is wrong with the record the command left, or nothing.
std::optional<std::string> record_problem(const JobSpec& spec, const std::string& hash) {
  const std::string path = spec.out_dir + "/" + job_files::kRecord;
  if (!fs::exists(path)) return "it wrote no " + std::string(job_files::kRecord) + " (rapid_harness.RunRecord.from_job writes it)";
  nlohmann::json record;
  try {
    record = read_json_input(path);
  } catch (const std::invalid_argument&) {
  }
  if (!record.is_object() || record.value("schema", "") != kRunRecordSchema)
    return "its " + std::string(job_files::kRecord) + " is not a run record";
  if (record.value("config_hash", "") != hash)
    return "its record's config_hash is not this job's (the script or its config changed while it ran, or it wrote "
           "another job's record)";
  if (record.value("status", "") != "ok")
    return "it recorded status '" + record.value("status", "?") + "'" +
           (record.contains("error") && record["error"].is_string() ? ": " + excerpt(record["error"].get<std::string>()) : "");
  return std::nullopt;
}

// The job and method a job document describes (the inverse of job_document).
ExternalJob parse_job(const nlohmann::json& document) {
  ExternalJob job;
  job.document = document;
  job.spec.scenario = document.at("scenario").get<std::string>();
  job.spec.algo = document.at("algo").get<std::string>();
  job.spec.seed = document.at("seed").get<std::uint64_t>();
  job.spec.config = document.at("config");
  job.spec.out_dir = document.at("out").get<std::string>();
  if (!document.at("dataset_path").is_null()) {
    job.spec.dataset_path = document["dataset_path"].get<std::string>();
    job.spec.dataset = document.at("dataset").get<std::string>();
  }
  job.method = describe_external_method(document.at("script").get<std::string>(), document.at("method_config"));
  job.method.command = document.at("command").get<std::vector<std::string>>();
  job.config_hash = document.at("config_hash").get<std::string>();
  return job;
}

}  // namespace

ExternalJob read_external_job(const std::string& path) {
  nlohmann::json document;
  try {
    document = read_json_input(path);
    if (!document.is_object() || document.value("schema", "") != kJobSchema)
      throw std::invalid_argument(std::string("not a job file (schema ") + kJobSchema + ") that rapid run writes");
    // Registered before the job is parsed: its hash covers the scenario file's files.
    if (document.contains("scenario_file") && document["scenario_file"].is_string())
      register_scenario_file(document.at("scenario").get<std::string>(), document["scenario_file"].get<std::string>());
    return parse_job(document);
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument("job " + path + ": " + e.what());
  } catch (const nlohmann::json::exception& e) {  // a field missing or of the wrong type
    throw std::invalid_argument("job " + path + ": " + e.what());
  }
}

int run_external_job(const JobSpec& spec, const ExternalMethod& method, const std::string& profile) {
  const std::string hash = external_config_hash(spec, method);
  fs::create_directories(spec.out_dir);
  const std::string job_path = fs::absolute(spec.out_dir + "/" + kJobFile).string();
  write_file_atomic(job_path, job_document(spec, method, profile, hash).dump(1));
  std::error_code ignored;
  fs::remove(spec.out_dir + "/" + job_files::kRecord, ignored);  // an earlier attempt's is not this one's

  std::vector<std::string> argv = method.command;
  argv.insert(argv.end(), {"--job", job_path});
  const CommandResult r = run_command(argv);
  const std::string who = "rapid run: " + spec.algo + "'s command";
  const std::string said = r.last_stderr_line.empty() ? "" : ": " + excerpt(r.last_stderr_line);
  if (r.signal != 0) {
    std::cerr << who << " was killed by signal " << r.signal << said << "\n";
    return 1;
  }
  if (r.exit_code != 0) {
    std::cerr << who << " exited with code " << r.exit_code << said << "\n";
    return 1;
  }
  if (const auto problem = record_problem(spec, hash)) {
    std::cerr << who << " exited 0 but " << *problem << "\n";
    return 1;
  }
  return 0;
}

}  // namespace rapid
