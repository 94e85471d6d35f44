#pragma once

#include <pybind11/pybind11.h>

#include <atomic>
#include <chrono>
#include <filesystem>
#include <functional>
#include <future>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>

#include "visgrab/database/database.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/request/grasp_request.hpp"

/// The C++ side of the Python module `visgrab` (the extension `visgrab._visgrab`; the package's
/// __init__.py adds the Python-level helpers). docs/python.md describes the interface.
namespace visgrab::python {

namespace py = pybind11;

/// An opened scene database and the path it was opened from (the runner opens it again).
struct OpenDatabase {
  /// The database, shared with the Scene objects made from it.
  std::shared_ptr<const database::Database> db;
  /// The path given to Database(path).
  std::filesystem::path path;
};

/// A loaded hand (the Python class Hand).
struct Hand {
  /// The prepared grasp description, shared by the copies Python makes.
  std::shared_ptr<const grasp::HandGraspSetup> setup;
  /// Its grasp description file (absolute).
  std::filesystem::path file;
};

/// One grasp (the Python class Grasp).
struct Grasp {
  /// The grasp as the grasp list reader made it.
  grasp::GraspRequest request;
};

/// An error raised as Python's OSError: a file that cannot be read or written.
class OsError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Registers Database, Scene and generate_database.
void bindDatabase(py::module_& m);
/// Registers Hand, Grasp and the grasp-file functions.
void bindGrasps(py::module_& m);
/// Registers TrialResult, Results, run, read_results and analyze.
void bindRuns(py::module_& m);
/// Registers the grasp importers' functions (import_grasps's C++ side).
void bindImporters(py::module_& m);

/// Runs `work(stop)` on a worker thread while the calling thread, without the GIL, looks at
/// Python's signals every 100 ms (PyErr_CheckSignals) and calls `tick` (with the GIL; e.g. a
/// progress callback). A pending KeyboardInterrupt (or an exception from `tick`) sets the stop
/// flag, waits for `work` to end (it finishes its running items, writes them and throws
/// rw::common::StopRequested), then is raised. Otherwise returns what `work` returned or throws
/// what it threw. Call with the GIL held.
template <typename Work>
auto runInterruptible(Work&& work, const std::function<void()>& tick = {})
    -> decltype(work(static_cast<const std::atomic<bool>*>(nullptr))) {
  using Result = decltype(work(static_cast<const std::atomic<bool>*>(nullptr)));
  std::atomic<bool> stop{false};
  std::packaged_task<Result()> task([&work, &stop] { return work(&stop); });
  std::future<Result> done = task.get_future();
  std::thread worker;
  {
    py::gil_scoped_release release;
    worker = std::thread(std::move(task));
  }
  std::optional<py::error_already_set> raised;
  for (;;) {
    std::future_status status;
    {
      py::gil_scoped_release release;
      status = done.wait_for(std::chrono::milliseconds(100));
    }
    if (status == std::future_status::ready) break;
    if (raised) continue;
    if (PyErr_CheckSignals() != 0) {
      raised.emplace();
      stop = true;
      continue;
    }
    if (tick) {
      try {
        tick();
      } catch (py::error_already_set& e) {
        raised.emplace(std::move(e));
        stop = true;
      }
    }
  }
  {
    py::gil_scoped_release release;
    worker.join();
  }
  if (raised) throw std::move(*raised);
  if (tick) tick();
  return done.get();
}

}  // namespace visgrab::python
