#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "common.hpp"
#include "visgrab/importers/grasp_import.hpp"

namespace visgrab::python {

namespace {

namespace fs = std::filesystem;

// What the importers give, as Python values: (grasps, rejections as "file: grasp i: why").
py::tuple resultTuple(importers::ImportResult&& result) {
  std::vector<Grasp> grasps;
  grasps.reserve(result.grasps.size());
  for (auto& g : result.grasps) grasps.push_back(Grasp{std::move(g)});
  std::vector<std::string> rejected;
  for (const auto& r : result.rejected) rejected.push_back(r.format());
  return py::make_tuple(grasps, rejected);
}

importers::ImportFormat formatOf(const std::string& name) {
  const auto format = importers::importFormatFromName(name);
  if (!format) {
    throw py::value_error("unknown format \"" + name +
                          "\", expected graspnet, contact-graspnet or acronym");
  }
  return *format;
}

// The scene (given, or for acronym the one made from `file`) and the importers' target.
importers::ImportTarget targetOf(importers::ImportFormat format, const fs::path& file,
                                 const OpenDatabase& db, const std::optional<std::string>& scene,
                                 const Hand& hand, const std::string& method) {
  if (!scene && format != importers::ImportFormat::kAcronym) {
    throw py::value_error(std::string(importers::importFormatName(format)) +
                          " grasps are in a scene's camera frame: give scene=");
  }
  const std::string id = scene ? *scene : importers::sceneMadeFrom(*db.db, file);
  return importers::importTarget(format, *db.db, id, *hand.setup, method);
}

// A numeric array as the importers' NdArray (C order, doubles).
importers::NdArray ndArrayOf(const py::array& array) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  if (!a) throw py::value_error("expected a numeric array");
  importers::NdArray out;
  for (py::ssize_t k = 0; k < a.ndim(); ++k)
    out.shape.push_back(static_cast<std::size_t>(a.shape(k)));
  out.values.assign(a.data(), a.data() + a.size());
  out.dtype = "numpy";
  return out;
}

template <typename F>
auto asOsError(F&& f) {
  try {
    return f();
  } catch (const importers::ImportError& e) {
    throw OsError(e.what());
  }
}

}  // namespace

void bindImporters(py::module_& m) {
  m.def(
      "_import_grasps",
      [](const std::string& format, const fs::path& file, const OpenDatabase& db,
         const std::optional<std::string>& scene, const Hand& hand, const std::string& method) {
        const importers::ImportFormat f = formatOf(format);
        return asOsError([&] {
          const importers::ImportTarget target = targetOf(f, file, db, scene, hand, method);
          importers::ImportResult result;
          {
            py::gil_scoped_release release;
            result = importers::importGraspFile(f, file, target);
          }
          return resultTuple(std::move(result));
        });
      },
      py::arg("format"), py::arg("file"), py::arg("db"), py::arg("scene"), py::arg("hand"),
      py::arg("method"), "import_grasps's C++ side: (grasps, rejections).");
  m.def(
      "_import_contact_graspnet_arrays",
      [](const py::array& grasps, const py::array& scores, const std::optional<py::array>& widths,
         const fs::path& file, const OpenDatabase& db, const std::optional<std::string>& scene,
         const Hand& hand, const std::string& method) {
        return asOsError([&] {
          const importers::ImportTarget target =
              targetOf(importers::ImportFormat::kContactGraspnet, file, db, scene, hand, method);
          std::optional<importers::NdArray> w;
          if (widths) w = ndArrayOf(*widths);
          return resultTuple(importers::importContactGraspnetArrays(
              ndArrayOf(grasps), ndArrayOf(scores), w, file.string(), target.X_W_frame,
              target.context));
        });
      },
      py::arg("grasps"), py::arg("scores"), py::arg("widths"), py::arg("file"), py::arg("db"),
      py::arg("scene"), py::arg("hand"), py::arg("method"),
      "import_grasps's C++ side for Contact-GraspNet arrays read in Python.");
}

}  // namespace visgrab::python
