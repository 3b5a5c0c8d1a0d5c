// _pqlayout: the C++ half of `import pqlayout` (python/pqlayout/__init__.py is the API users
// see and document). One function runs the pipeline in this process and hands back what the
// stages left in memory; the rest are the config reference and the version.
//
// Errors become Python exceptions with the CLI's one-line message: a config that does not
// parse or validate → pqlayout.ConfigError; bad input met while running (a mesh file, a
// boundary rule's ids file) → pqlayout.InputError; a run that could not complete →
// pqlayout.RunError; all three derive from pqlayout.Error. Never a crash of the interpreter:
// std::bad_alloc becomes MemoryError (pybind11), other C++ exceptions RuntimeError.
//
// Threads and the GIL: the run releases the GIL. The progress callback and the stop poll take
// it back briefly: the poll (base/interrupt.h) runs before every stage and at every solver
// iteration and calls PyErr_CheckSignals, so Ctrl-C in the interpreter stops the run within
// one iteration and raises KeyboardInterrupt; an exception raised by the progress callback
// stops it the same way and is re-raised. The pipeline keeps process-wide state (the stop
// flag, the numeric thread count), so runs in one process are serialised by a mutex; runs
// from several Python threads take turns.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <glog/logging.h>
#include <signal.h>
#include <stdlib.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "base/interrupt.h"
#include "pipeline/build_info.h"
#include "pipeline/config.h"
#include "pipeline/pipeline.h"
#include "python/module_arrays.h"

namespace py = pybind11;

namespace pqlayout::python {
namespace {

struct Error : std::runtime_error {
  using std::runtime_error::runtime_error;
};
struct ConfigError : Error {
  using Error::Error;
};
struct InputError : Error {
  using Error::Error;
};
struct RunError : Error {
  using Error::Error;
};

// What the GIL-free run and the Python side share while a run is on. Its Python objects are
// only touched with the GIL.
struct RunContext {
  py::object progress;                     // None or a callable (stage, event, seconds)
  std::optional<py::error_already_set> error;  // raised by the callback or Ctrl-C
};
// The run in progress on this thread. The poll and the progress callback are called on the
// thread that runs the pipeline (before each stage, from Ceres' iteration callback), which
// is the thread that called run(): thread-local, so another thread's run never sees it.
thread_local RunContext* g_context = nullptr;

// Sets g_context for its lifetime, and clears it however the run ends (a C++ exception too).
class ContextScope {
 public:
  explicit ContextScope(RunContext* context) { g_context = context; }
  ~ContextScope() { g_context = nullptr; }
  ContextScope(const ContextScope&) = delete;
  ContextScope& operator=(const ContextScope&) = delete;
};

// The stop poll: Ctrl-C pending in Python, or an exception already caught from the callback.
int PollPython() {
  if (g_context == nullptr) return 0;  // not a thread running a Python-started pipeline
  py::gil_scoped_acquire gil;
  if (g_context->error) return SIGINT;
  if (PyErr_CheckSignals() != 0) {
    g_context->error.emplace();  // fetches the KeyboardInterrupt (or the handler's exception)
    return SIGINT;
  }
  return 0;
}

void ReportProgress(const std::string& stage, const std::string& event, double seconds) {
  if (g_context == nullptr) return;
  py::gil_scoped_acquire gil;
  if (g_context->progress.is_none() || g_context->error) return;
  try {
    g_context->progress(stage, event, seconds);
  } catch (py::error_already_set& e) {
    g_context->error.emplace(std::move(e));
  }
}

// Progress lines as the CLI writes them, "[   1.2 s] stage: ...", to stderr (verbose runs).
void LogPrefix(std::ostream& s, const google::LogMessageInfo& info, void*) {
  static const auto start = std::chrono::steady_clock::now();
  char stamp[32];
  std::snprintf(stamp, sizeof(stamp), "[%7.2f s]",
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  s << "pqlayout " << stamp;
  if (info.severity[0] == 'W') s << " warning:";
  if (info.severity[0] == 'E' || info.severity[0] == 'F') s << " error:";
}

// A private folder for a run whose files nobody asked for; removed again afterwards.
class TemporaryFolder {
 public:
  TemporaryFolder() {
    std::string pattern = (std::filesystem::temp_directory_path() / "pqlayout-XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) throw RunError("cannot create a temporary folder in " + pattern);
    path_ = pattern;
  }
  ~TemporaryFolder() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
};

// config_path or config_text (YAML/JSON, relative paths against the working directory).
Config LoadOrThrow(const std::optional<std::string>& config_path, const std::optional<std::string>& config_text,
                   const std::vector<std::string>& sets) {
  Config config;
  const Status status = config_path ? LoadConfig(*config_path, sets, &config)
                                    : ParseConfig(*config_text, "config dict", std::filesystem::current_path().string(),
                                                  sets, &config);
  if (!status.ok()) throw ConfigError(OneLine(status.message()));
  return config;
}

py::dict Run(const std::optional<std::string>& config_path, const std::optional<std::string>& config_text,
             const std::vector<std::string>& sets, const std::string& until, const std::optional<std::string>& out,
             py::object progress, bool verbose) {
  static std::mutex one_run_at_a_time;
  const Config config = LoadOrThrow(config_path, config_text, sets);
  RunOptions options;
  const std::optional<Stage> last = StageFromName(until);
  if (!last) throw ConfigError("until: unknown stage '" + until + "' (surface, membrane, guidance, levelset, "
                               "extract, planarize, stiffen or analyze)");
  options.until = *last;
  options.config_path = config_path ? *config_path : "(config dict)";
  options.command_line = "pqlayout.run (Python module)";
  std::optional<TemporaryFolder> scratch;
  if (out) {
    options.out_dir = *out;
  } else {
    scratch.emplace();
    options.out_dir = scratch->path() + "/run";
    options.commit = false;
  }
  options.progress = &ReportProgress;
  RunContext context{std::move(progress), std::nullopt};
  const ContextScope scope(&context);  // cleared after the GIL is back, even if the run throws
  nlohmann::json report;
  PipelineState state;
  Status status;
  {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(one_run_at_a_time);  // process-wide: the stop flag, thread counts
    FLAGS_minloglevel = verbose ? google::GLOG_INFO : google::GLOG_WARNING;
    ClearInterrupt();
    status = RunPipeline(config, options, &report, &state);
    ClearInterrupt();
  }
  if (context.error) throw std::move(*context.error);  // Ctrl-C or the callback's exception
  if (!status.ok()) {
    const std::string message = OneLine(status.message());
    if (status.code() == StatusCode::kInvalidInput) throw InputError(message);
    throw RunError(message);
  }
  const std::vector<std::string> completed = report["run"]["completed_stages"].get<std::vector<std::string>>();
  py::dict result = StateToDict(state, completed);
  result["report"] = py::str(report.dump());
  return result;
}

}  // namespace
}  // namespace pqlayout::python

PYBIND11_MODULE(_pqlayout, m) {
  using namespace pqlayout::python;
  m.doc() = "pqlayout's C++ pipeline; use the `pqlayout` package, not this module.";
  static py::exception<Error> error(m, "Error");
  py::register_exception<ConfigError>(m, "ConfigError", error.ptr());
  py::register_exception<InputError>(m, "InputError", error.ptr());
  py::register_exception<RunError>(m, "RunError", error.ptr());

  if (!google::IsGoogleLoggingInitialized()) {
    FLAGS_logtostderr = true;
    FLAGS_colorlogtostderr = false;
    FLAGS_minloglevel = google::GLOG_WARNING;
    google::InitGoogleLogging("pqlayout", &LogPrefix, nullptr);
  }
  pqlayout::SetInterruptPoll(&PollPython);

  m.def("run", &Run, py::arg("config_path"), py::arg("config_text"), py::arg("sets"), py::arg("until"),
        py::arg("out"), py::arg("progress"), py::arg("verbose"));
  m.def("keys", [] { return pqlayout::ConfigReference().dump(); }, "The config reference as JSON text.");
  m.def("version", [] {
    const auto& info = pqlayout::GetBuildInfo();
    return info.version + " (git " + info.git_revision + ")";
  });
  m.def("stages", [] { return pqlayout::StageNames(); });
}
