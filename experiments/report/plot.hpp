// Running scripts/plot (matplotlib, Figures 2 and 3) after `rapid summarize`. Plots are drawn by
// Debian's /usr/bin/python3 (not a pyenv shim, whose python may lack matplotlib); RAPID_PYTHON overrides the interpreter.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace rapid {

// fork + exec of argv[0] (a path; no shell, so paths may hold spaces); stdout and stderr silenced
// when `quiet`. Returns the exit code, -1 when it could not be started or was killed.
int run_command(const std::vector<std::string>& argv, bool quiet);

// scripts/plot from the source tree this binary was built from, else next to the binary
// (BIN_DIR/scripts/plot or BIN_DIR/../scripts/plot); nullopt if none exists.
std::optional<std::filesystem::path> find_plot_script();

// The interpreter: $RAPID_PYTHON if set, else /usr/bin/python3.
std::string plot_python();

// Whether the interpreter runs and can import matplotlib.
bool python_has_matplotlib(const std::string& python);

// How a script ended: its exit code, or the signal that killed it; `interrupted` when rapid
// itself caught a stop signal meanwhile and stopped it (interruption.hpp).
struct ScriptExit {
  int code = -1;  // -1: not started, or killed by `signal`
  int signal = 0;
  bool interrupted = false;
  bool ok() const { return code == 0 && !interrupted; }
};

// Runs PYTHON SCRIPT --summary SUMMARY_JSON --out OUT_DIR and waits for it.
ScriptExit run_plot_script(const std::string& python, const std::filesystem::path& script,
                    const std::filesystem::path& summary_json, const std::filesystem::path& out_dir);

}  // namespace rapid
