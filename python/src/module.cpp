#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <string>

#include "cli_common/data_folder.hpp"
#include "common.hpp"
#include "rw/common/diagnostic.hpp"
#include "rw/common/stop_signals.hpp"
#include "rw/common/write_error.hpp"
#include "visgrab/database/scene_filter.hpp"

namespace {

namespace py = pybind11;

// C++ exceptions as Python's: bad input is ValueError, files are OSError (the message is the
// CLI's: file:line:column where the C++ side knows them).
// By value: pybind11's translator signature.
void translate(std::exception_ptr error) {  // NOLINT(performance-unnecessary-value-param)
  namespace db = visgrab::database;
  try {
    if (error) std::rethrow_exception(error);
  } catch (const rw::common::LoadError& e) {
    PyErr_SetString(PyExc_OSError, e.what());
  } catch (const rw::common::WriteError& e) {
    PyErr_SetString(PyExc_OSError, e.what());
  } catch (const visgrab::python::OsError& e) {
    PyErr_SetString(PyExc_OSError, e.what());
  } catch (const db::UnknownSceneError& e) {
    PyErr_SetString(PyExc_ValueError, e.what());
  } catch (const db::CalibrationError& e) {
    PyErr_SetString(PyExc_OSError, e.what());
  } catch (const db::PointCloudError& e) {
    PyErr_SetString(PyExc_OSError, e.what());
  } catch (const db::DatabaseError& e) {
    PyErr_SetString(PyExc_OSError, e.what());
  } catch (const db::FilterError& e) {
    PyErr_SetString(PyExc_ValueError, e.what());
  } catch (const rw::common::StopRequested& e) {
    PyErr_SetString(PyExc_KeyboardInterrupt, e.what());
  }
}

}  // namespace

PYBIND11_MODULE(_visgrab, m) {
  m.doc() = "The C++ side of the visgrab package (import visgrab; docs/python.md).";
  m.attr("__version__") = VISGRAB_VERSION;
  m.attr("_source_scenes") = VISGRAB_SCENES_DIR;
  py::register_exception_translator(&translate);
  m.def(
      "_default_data_folder",
      [](const std::filesystem::path& prefix) {
        // As the installed `visgrab` program finds its data: the installed data next to it
        // (PREFIX/bin/visgrab -> PREFIX/share/visgrab/scenes), else the source tree's.
        std::filesystem::path installed =
            visgrab::cli::installedDataFolder(prefix / "bin" / "visgrab");
        std::error_code error;
        if (std::filesystem::is_directory(installed, error)) return installed;
        return std::filesystem::path(VISGRAB_SCENES_DIR);
      },
      py::arg("prefix"),
      "The scene data folder of a package installed under `prefix`, else the source tree's.");
  visgrab::python::bindDatabase(m);
  visgrab::python::bindGrasps(m);
  visgrab::python::bindRuns(m);
  visgrab::python::bindImporters(m);
}
