#include "experiments/sweep/slurm_backend.hpp"

#include <fcntl.h>
#include <poll.h>
#include <pwd.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <iterator>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <set>
#include <sstream>

#include "core/atomic_file.hpp"
#include "experiments/run/provenance.hpp"

namespace rapid {

namespace fs = std::filesystem;

namespace {

inline constexpr const char* kSlurmDir = "slurm";
inline constexpr const char* kSubmissions = "slurm/submissions.json";
inline constexpr const char* kSubmissionsSchema = "rapid.slurm/1";

const char* stage_name(JobKind kind) {
  switch (kind) {
    case JobKind::kReference: return "references";
    case JobKind::kDatasets: return "datasets";
    case JobKind::kCell: break;
  }
  return "cells";
}

// slurm/20250101T120000Z, with -2, -3, … if a submission in the same second exists.
std::string submission_folder(const SweepFolder& folder) {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  ::gmtime_r(&now, &utc);
  char stamp[32];
  std::strftime(stamp, sizeof stamp, "%Y%m%dT%H%M%SZ", &utc);
  const std::string base = std::string(kSlurmDir) + "/" + stamp;
  std::string name = base;
  for (int n = 2; fs::exists(folder.path(name)); ++n) name = base + "-" + std::to_string(n);
  return name;
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

struct CommandResult {
  int exit_code = -1;
  std::string out, err;
};

// Runs a program found on PATH with stdout and stderr captured separately (sbatch --parsable
// prints the id on stdout and warnings on stderr). Throws SlurmError if it cannot be started.
CommandResult run_command(const std::vector<std::string>& argv_strings) {
  int out_pipe[2], err_pipe[2];
  if (::pipe2(out_pipe, O_CLOEXEC) != 0 || ::pipe2(err_pipe, O_CLOEXEC) != 0)
    throw SlurmError(std::string("cannot create a pipe: ") + std::strerror(errno));
  std::vector<std::string> copy = argv_strings;
  std::vector<char*> argv;
  for (auto& s : copy) argv.push_back(s.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) throw SlurmError(std::string("fork failed: ") + std::strerror(errno));
  if (pid == 0) {
    ::dup2(out_pipe[1], 1);
    ::dup2(err_pipe[1], 2);
    ::execvp(argv[0], argv.data());
    ::_exit(127);
  }
  ::close(out_pipe[1]);
  ::close(err_pipe[1]);
  CommandResult result;
  pollfd fds[2] = {{out_pipe[0], POLLIN, 0}, {err_pipe[0], POLLIN, 0}};
  std::string* sinks[2] = {&result.out, &result.err};
  int open_fds = 2;
  while (open_fds > 0) {
    if (::poll(fds, 2, -1) < 0) {
      if (errno == EINTR) continue;
      break;
    }
    for (int i = 0; i < 2; ++i) {
      if (fds[i].fd < 0 || !(fds[i].revents & (POLLIN | POLLHUP | POLLERR))) continue;
      char buf[4096];
      const ssize_t n = ::read(fds[i].fd, buf, sizeof buf);
      if (n > 0) {
        sinks[i]->append(buf, static_cast<std::size_t>(n));
      } else if (n == 0 || errno != EINTR) {
        ::close(fds[i].fd);
        fds[i].fd = -1;
        --open_fds;
      }
    }
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
  if (result.exit_code == 127)
    throw SlurmError("cannot run " + argv_strings[0] + ": is Slurm installed and on PATH (or SLURM_CONF set)?");
  return result;
}

// The first non-empty line of a command's error output, for one-line messages.
std::string first_line(const std::string& text) {
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
    if (line.find_first_not_of(" \t\r") != std::string::npos) return line;
  return "";
}

nlohmann::json read_submissions(const SweepFolder& folder) {
  const auto j = read_json_file(folder.path(kSubmissions));
  if (j && j->is_object() && j->contains("submissions") && (*j)["submissions"].is_array()) return *j;
  return {{"schema", kSubmissionsSchema}, {"submissions", nlohmann::json::array()}};
}

// The sweep folder as the scripts name it: absolute, without a trailing slash.
std::string absolute_folder(const SweepFolder& folder) {
  const std::string dir = fs::absolute(folder.dir).lexically_normal().string();
  return dir.size() > 1 && dir.back() == '/' ? dir.substr(0, dir.size() - 1) : dir;
}

// Where and how long a job may run, and the user's own sbatch options: the same for every job
// of a submission.
void placement_lines(std::ostream& s, const SlurmOptions& o) {
  if (!o.partition.empty()) s << "#SBATCH --partition=" << o.partition << "\n";
  if (!o.time.empty()) s << "#SBATCH --time=" << o.time << "\n";
  for (const auto& arg : o.sbatch_args) s << "#SBATCH " << arg << "\n";
}

// sbatch --parsable's output → the job id, or empty if it is not one.
std::string parsed_job_id(const CommandResult& r) {
  const std::string id = r.out.substr(0, r.out.find_first_of(";\n"));  // "id" or "id;cluster"
  return r.exit_code != 0 || id.empty() || id.find_first_not_of("0123456789") != std::string::npos ? "" : id;
}

}  // namespace

std::size_t SlurmPlan::tasks() const {
  std::size_t n = 0;
  for (const auto& a : arrays) n += a.tasks.size();
  return n;
}

SlurmPlan plan_slurm_sweep(const SweepFolder& folder, const Selection& selection, bool force) {
  SlurmPlan plan;
  plan.submission = submission_folder(folder);
  const std::vector<SweepJob>& jobs = folder.graph.jobs;
  const std::vector<bool> needed = selected_with_dependencies(selection, folder.graph);
  std::vector<bool> submitted(jobs.size(), false);
  std::vector<std::size_t> array_of(jobs.size(), 0);
  for (std::size_t i = 0; i < jobs.size(); ++i) {
    if (!needed[i]) continue;
    ++plan.needed;
    const SweepJob& job = jobs[i];
    const bool forced = force && selects(selection, job);
    const bool after_rerun = std::any_of(job.deps.begin(), job.deps.end(), [&](std::size_t d) { return submitted[d]; });
    if (!forced && !after_rerun && job_is_done(folder, job)) {
      ++plan.done;
      continue;
    }
    submitted[i] = true;
    // One array per (stage, scenario, arrays it must wait for): scenarios never wait for each
    // other, and cells with nothing to wait for do not wait for the datasets of the others.
    std::vector<std::size_t> after;
    for (std::size_t d : job.deps)
      if (submitted[d]) after.push_back(array_of[d]);
    std::sort(after.begin(), after.end());
    after.erase(std::unique(after.begin(), after.end()), after.end());
    const std::string stage = stage_name(job.kind);
    auto same = [&](const SlurmArray& a) { return a.stage == stage && a.scenario == job.scenario && a.after == after; };
    auto it = std::find_if(plan.arrays.begin(), plan.arrays.end(), same);
    if (it == plan.arrays.end()) {
      SlurmArray& array = plan.arrays.emplace_back();
      array.stage = stage;
      array.scenario = job.scenario;
      array.after = after;
      it = std::prev(plan.arrays.end());
    }
    array_of[i] = static_cast<std::size_t>(it - plan.arrays.begin());
    it->tasks.push_back({job.id(), forced});
  }
  for (SlurmArray& a : plan.arrays) {
    a.name = a.stage + "-" + a.scenario;
    const bool twin = std::count_if(plan.arrays.begin(), plan.arrays.end(), [&](const SlurmArray& b) {
                        return b.stage == a.stage && b.scenario == a.scenario;
                      }) > 1;
    if (twin && a.after.empty()) a.name += "-independent";
    a.list = plan.submission + "/" + a.name + ".json";
    a.script = plan.submission + "/" + a.name + ".sbatch";
  }
  return plan;
}

std::string sbatch_script(const SweepFolder& folder, const SlurmPlan& plan, std::size_t a, const std::string& after,
                          const SlurmOptions& o) {
  const SlurmArray& array = plan.arrays.at(a);
  const std::string base = absolute_folder(folder);
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# rapid sweep " << folder.grid.name << ", array " << a + 1 << "/" << plan.arrays.size() << ", "
    << array.name << ": " << array.tasks.size() << " task" << (array.tasks.size() == 1 ? "" : "s")
    << " (written by `rapid sweep --backend slurm`).\n"
    << "# Task I runs job I of " << array.list << " (in the sweep folder).\n"
    << "# The job's own output goes to its log.txt, the task's to the --output file.\n"
    << "# Progress: rapid status " << base << "\n"
    << "#SBATCH --job-name=rapid-" << folder.grid.name << "-" << array.name << "\n"
    << "#SBATCH --array=0-" << array.tasks.size() - 1 << "%" << o.array_parallelism << "\n"
    << "#SBATCH --chdir=" << base << "\n"
    << "#SBATCH --output=" << base << "/" << kSlurmDir << "/" << array.name << "_%A_%a.out\n"
    << "#SBATCH --ntasks=1\n"
    << "#SBATCH --cpus-per-task=" << o.cpus_per_task << "\n";
  placement_lines(s, o);
  if (!after.empty()) {
    // afterok on an array waits for every task of it; if one fails this array can never start,
    // and Slurm cancels it rather than leaving it pending forever.
    s << "#SBATCH --dependency=afterok:" << after << "\n"
      << "#SBATCH --kill-on-invalid-dep=yes\n";
  }
  // A job's OpenMP threads (a critic ensemble's members) use the CPUs of its task, no more.
  s << "export OMP_NUM_THREADS=" << o.cpus_per_task << "\n";
  s << "exec " << shell_quote(o.binary) << " sweep . --run-job \"$SLURM_ARRAY_TASK_ID\" --job-list "
    << shell_quote(array.list) << "\n";
  return s.str();
}

void submit_slurm_plan(const SweepFolder& folder, SlurmPlan& plan, const SlurmOptions& options) {
  fs::create_directories(folder.path(plan.submission));
  nlohmann::json submissions = read_submissions(folder);
  nlohmann::json record = {{"submitted", utc_now_iso8601()}, {"folder", plan.submission}, {"arrays", nlohmann::json::array()}};
  auto save = [&] {
    nlohmann::json all = submissions;
    all["submissions"].push_back(record);
    write_file_atomic(folder.path(kSubmissions).string(), all.dump(1));
  };
  for (std::size_t a = 0; a < plan.arrays.size(); ++a) {
    SlurmArray& array = plan.arrays[a];
    std::string after;
    for (std::size_t k : array.after) after += (after.empty() ? "" : ":") + plan.arrays[k].job_id;
    write_task_list(folder.path(array.list), array.stage, array.tasks);
    write_file_atomic(folder.path(array.script).string(), sbatch_script(folder, plan, a, after, options));
    const CommandResult r = run_command({"sbatch", "--parsable", folder.path(array.script).string()});
    const std::string id = parsed_job_id(r);
    if (id.empty()) {
      std::string message = "sbatch failed for the " + array.name + " array: " +
                            first_line(r.err.empty() ? r.out : r.err);
      if (record["arrays"].empty()) {
        fs::remove_all(folder.path(plan.submission));  // nothing was submitted: leave no trace
      } else {
        save();
        message += " (already submitted:";
        for (const auto& done : record["arrays"])
          message.append(" ").append(done["name"].get<std::string>()).append(" ").append(done["job_id"].get<std::string>());
        message += "; scancel them or let them run, then submit again)";
      }
      throw SlurmError(message);
    }
    array.job_id = id;
    record["arrays"].push_back({{"stage", array.stage},
                                {"scenario", array.scenario},
                                {"name", array.name},
                                {"job_id", id},
                                {"tasks", array.tasks.size()},
                                {"after", after.empty() ? nlohmann::json(nullptr) : nlohmann::json(after)},
                                {"list", array.list}});
  }
  save();
}

std::string submit_slurm_follow_up(const SweepFolder& folder, const SlurmPlan& plan, const std::string& name,
                                   const std::vector<std::string>& arguments, const SlurmOptions& o) {
  std::string after, command = "exec " + shell_quote(o.binary);
  for (const SlurmArray& a : plan.arrays) after += (after.empty() ? "" : ":") + a.job_id;
  for (const std::string& argument : arguments) command += " " + shell_quote(argument);
  const std::string base = absolute_folder(folder), script = plan.submission + "/" + name + ".sbatch";
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# rapid sweep " << folder.grid.name << ", " << name << ": runs once every array of " << plan.submission
    << " has ended, whatever their outcome (written by `rapid sweep --backend slurm`).\n"
    << "#SBATCH --job-name=rapid-" << folder.grid.name << "-" << name << "\n"
    << "#SBATCH --chdir=" << base << "\n"
    << "#SBATCH --output=" << base << "/" << kSlurmDir << "/" << name << "_%j.out\n"
    << "#SBATCH --ntasks=1\n"
    << "#SBATCH --cpus-per-task=1\n";
  placement_lines(s, o);
  if (!after.empty()) s << "#SBATCH --dependency=afterany:" << after << "\n";
  s << command << "\n";
  fs::create_directories(folder.path(plan.submission));
  write_file_atomic(folder.path(script).string(), s.str());
  const CommandResult r = run_command({"sbatch", "--parsable", folder.path(script).string()});
  const std::string id = parsed_job_id(r);
  if (id.empty())
    throw SlurmError("sbatch failed for " + name + ": " + first_line(r.err.empty() ? r.out : r.err) +
                     " (the arrays of " + plan.submission + " stay submitted)");
  nlohmann::json submissions = read_submissions(folder);
  nlohmann::json* record = nullptr;
  for (auto& sub : submissions["submissions"])
    if (sub.value("folder", "") == plan.submission) record = &sub;
  if (!record) {
    submissions["submissions"].push_back({{"submitted", utc_now_iso8601()}, {"folder", plan.submission}, {"arrays", nlohmann::json::array()}});
    record = &submissions["submissions"].back();
  }
  (*record)["arrays"].push_back({{"stage", name}, {"name", name}, {"job_id", id}, {"tasks", 1},
                                 {"after", after.empty() ? nlohmann::json(nullptr) : nlohmann::json(after)}});
  write_file_atomic(folder.path(kSubmissions).string(), submissions.dump(1));
  return id;
}

std::vector<std::string> queued_slurm_jobs(const SweepFolder& folder) {
  std::set<std::string> ours;
  const nlohmann::json submissions = read_submissions(folder);
  for (const auto& s : submissions["submissions"])
    for (const auto& a : s.value("arrays", nlohmann::json::array()))
      if (a.contains("job_id") && a["job_id"].is_string()) ours.insert(a["job_id"].get<std::string>());
  if (ours.empty()) return {};
  // %F is the array's job id for every task (the plain id for other jobs). squeue lists pending,
  // running and completing jobs by default, not finished ones.
  const passwd* pw = ::getpwuid(::getuid());
  std::vector<std::string> argv = {"squeue", "--noheader", "--format=%F"};
  if (pw) argv.push_back(std::string("--user=") + pw->pw_name);
  const CommandResult r = run_command(argv);
  if (r.exit_code != 0) throw SlurmError("squeue failed: " + first_line(r.err.empty() ? r.out : r.err));
  std::set<std::string> queued;
  std::istringstream in(r.out);
  for (std::string id; in >> id;)
    if (ours.count(id)) queued.insert(id);
  return {queued.begin(), queued.end()};
}

void check_sbatch_args(const std::vector<std::string>& args) {
  // Options rapid writes itself: overriding them would break the task ↔ job mapping or the logs.
  static const std::vector<std::string> reserved = {"--array", "--chdir", "--output", "--error",
                                                    "--dependency", "--parsable", "--wrap", "--job-name",
                                                    "-a", "-D", "-o", "-e", "-d", "-J"};
  for (const auto& arg : args) {
    if (arg.empty() || arg[0] != '-')
      throw std::invalid_argument("--sbatch-arg: '" + arg + "' is not an sbatch option (write --sbatch-arg=--mem=4G)");
    const std::string name = arg.substr(0, arg.find_first_of("= "));
    for (const auto& r : reserved)
      if (name == r || (r.size() == 2 && arg.rfind(r, 0) == 0 && arg.size() > 2 && arg[1] != '-'))
        throw std::invalid_argument("--sbatch-arg: '" + arg + "' is set by rapid sweep itself");
  }
}

bool program_on_path(const std::string& program) {
  const char* path = std::getenv("PATH");
  if (path == nullptr) return false;
  std::string dirs = path;
  for (std::size_t start = 0; start <= dirs.size();) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const std::string dir = end > start ? dirs.substr(start, end - start) : ".";
    if (::access((dir + "/" + program).c_str(), X_OK) == 0) return true;
    start = end + 1;
  }
  return false;
}

}  // namespace rapid
