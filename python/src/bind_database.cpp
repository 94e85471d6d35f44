#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <cstring>
#include <mutex>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "common.hpp"
#include "visgrab/database/scene_filter.hpp"
#include "visgrab/database/scene_set.hpp"
#include "visgrab/generator/generator.hpp"
#include "visgrab/generator/scene_model.hpp"
#include "visgrab/objects/object_spec.hpp"

namespace visgrab::python {

namespace {

namespace fs = std::filesystem;

// A scene of an open database (the Python class Scene).
struct SceneView {
  std::shared_ptr<const database::Database> db;
  database::SceneEntry entry;
};

// A dense row-major copy of an Eigen matrix as a 2-D float64 array.
template <typename Matrix>
py::array_t<double> matrixArray(const Matrix& m) {
  py::array_t<double> out({static_cast<py::ssize_t>(m.rows()), static_cast<py::ssize_t>(m.cols())});
  auto view = out.mutable_unchecked<2>();
  for (Eigen::Index r = 0; r < m.rows(); ++r) {
    for (Eigen::Index c = 0; c < m.cols(); ++c) view(r, c) = m(r, c);
  }
  return out;
}

// A vector as a 1-D float64 array.
template <typename Vector>
py::array_t<double> vectorArray(const Vector& v) {
  py::array_t<double> out(static_cast<py::ssize_t>(v.size()));
  auto view = out.mutable_unchecked<1>();
  for (Eigen::Index i = 0; i < v.size(); ++i) view(i) = v(i);
  return out;
}

// A copy of an 8-bit, 16-bit or float image (1 or 3 channels) as an HxW or HxWxC array.
template <typename T>
py::array imageArray(const cv::Mat& image) {
  std::vector<py::ssize_t> shape = {image.rows, image.cols};
  if (image.channels() > 1) shape.push_back(image.channels());
  py::array_t<T> out(shape);
  const std::size_t rowBytes = static_cast<std::size_t>(image.cols) * image.elemSize();
  auto* dst = reinterpret_cast<unsigned char*>(out.mutable_data());
  for (int r = 0; r < image.rows; ++r) std::memcpy(dst + r * rowBytes, image.ptr(r), rowBytes);
  return out;
}

// Any image cv::imread gives, as an array of its own depth.
py::array anyImageArray(const cv::Mat& image) {
  switch (image.depth()) {
    case CV_8U:
      return imageArray<std::uint8_t>(image);
    case CV_16U:
      return imageArray<std::uint16_t>(image);
    case CV_32F:
      return imageArray<float>(image);
    default:
      throw database::DatabaseError("image of an unsupported pixel type (OpenCV depth " +
                                    std::to_string(image.depth()) + ")");
  }
}

// An image file as the database stores it (cv::IMREAD_UNCHANGED), or None without one.
py::object rawImage(const fs::path& file) {
  if (file.empty()) return py::none();
  cv::Mat image;
  {
    py::gil_scoped_release release;
    image = cv::imread(file.string(), cv::IMREAD_UNCHANGED);
  }
  if (image.empty()) {
    throw database::DatabaseError(file.string() + ": missing or not a readable image");
  }
  return anyImageArray(image);
}

// A colour image (BGR from OpenCV) as HxWx3 uint8 in RGB order.
py::array rgbArray(const cv::Mat& bgr) {
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  return imageArray<std::uint8_t>(rgb);
}

/// A Scene property that reads one of the scene's images with `read` (a Database member) without
/// the GIL and gives it to Python with `convert`.
template <typename Read, typename Convert>
auto sceneImage(Read read, Convert convert) {
  return [read, convert](const SceneView& s) {
    cv::Mat image;
    {
      py::gil_scoped_release release;
      image = read(*s.db, s.entry.id);
    }
    return convert(image);
  };
}

py::object conditionsDict(const std::optional<database::SceneConditions>& c,
                          const database::ObjectCatalog& catalog) {
  if (!c) return py::none();
  py::dict d;
  d["texture"] = std::string(database::toString(c->texture));
  d["kind"] = std::string(database::toString(c->kind));
  d["arrangement"] = std::string(database::toString(c->arrangement()));
  py::list names;
  for (const int o : c->objects) names.append(std::string(catalog.name(o)));
  d["objects"] = names;
  d["object_ids"] = c->objects;
  d["pose"] = c->pose;
  d["description"] = database::describe(*c, catalog);
  return d;
}

py::dict calibrationDict(const database::StereoCalibration& k) {
  py::dict d;
  d["width"] = k.width;
  d["height"] = k.height;
  d["K1"] = matrixArray(k.K1);
  d["D1"] = vectorArray(k.D1);
  d["K2"] = matrixArray(k.K2);
  d["D2"] = vectorArray(k.D2);
  d["R"] = matrixArray(k.R);
  d["T"] = vectorArray(k.T);
  d["R1"] = matrixArray(k.R1);
  d["R2"] = matrixArray(k.R2);
  d["P1"] = matrixArray(k.P1);
  d["P2"] = matrixArray(k.P2);
  d["Q"] = matrixArray(k.Q);
  d["X_table_left"] = matrixArray(k.X_TL.matrix());
  d["X_table_camera"] = matrixArray(k.rectifiedLeftPose().matrix());
  d["baseline"] = k.baseline();
  return d;
}

py::dict filesDict(const database::SceneEntry& s) {
  py::dict d;
  auto put = [&d](const char* name, const fs::path& file) {
    d[name] = file.empty() ? py::object(py::none()) : py::object(py::cast(file.string()));
  };
  put("left_image", s.leftImage);
  put("right_image", s.rightImage);
  put("calibration", s.calibration);
  put("workcell", s.workcell);
  put("dynamic_workcell", s.dynamicWorkcell);
  put("raw_left_image", s.rawLeftImage);
  put("raw_right_image", s.rawRightImage);
  put("disparity", s.disparity);
  put("point_cloud", s.pointCloud);
  put("depth", s.depth);
  put("mask", s.mask);
  put("poses", s.poses);
  put("collision_mesh", s.collision);
  return d;
}

// The cloud as Nx6 float64 (x y z r g b), its points moved by X (identity: as stored).
py::array_t<double> cloudArray(const database::PointCloud& cloud, const Eigen::Isometry3d& X) {
  py::array_t<double> out({static_cast<py::ssize_t>(cloud.points.size()), py::ssize_t{6}});
  auto view = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < cloud.points.size(); ++i) {
    const Eigen::Vector3d p = X * cloud.points[i].cast<double>();
    const auto n = static_cast<py::ssize_t>(i);
    for (int c = 0; c < 3; ++c) view(n, c) = p(c);
    for (int c = 0; c < 3; ++c) view(n, 3 + c) = cloud.colours[i][static_cast<std::size_t>(c)];
  }
  return out;
}

database::SceneFilter parseFilter(const py::object& filter,
                                  const database::ObjectCatalog& catalog) {
  if (filter.is_none()) return {};
  if (py::isinstance<py::str>(filter)) {
    return database::SceneFilter::parse(filter.cast<std::string>(), catalog);
  }
  return database::SceneFilter::parse(filter.cast<std::vector<std::string>>(), catalog);
}

std::vector<std::string> sceneIds(const OpenDatabase& d, const py::object& filter) {
  std::vector<std::string> ids;
  for (const auto* s : d.db->filter(parseFilter(filter, d.db->catalog()))) ids.push_back(s->id);
  return ids;
}

SceneView sceneOf(const OpenDatabase& d, const std::string& id) { return {d.db, d.db->scene(id)}; }

// generate_database: `visgrab db generate` with these options.
py::dict generate(const fs::path& out, const py::object& scenes, int threads,
                  const std::string& camera, std::uint64_t seed, const fs::path& data,
                  const py::object& objects, const py::object& progress) {
  if (threads < 1) throw py::value_error("threads must be >= 1, got " + std::to_string(threads));
  generator::GeneratorOptions options;
  options.objectSpec = data / "objects" / "objects.xml";
  if (!objects.is_none()) {
    const auto spec = objects.cast<fs::path>();
    options.catalog = generator::objectCatalog(objects::loadObjectSpecs(spec));
    options.tableSpec = options.objectSpec;
    options.objectSpec = spec;
  }
  database::SceneFilter filter;
  try {
    filter = parseFilter(scenes, options.catalog);
  } catch (const database::FilterError& e) {
    throw py::value_error(std::string("scenes: ") + e.what());
  }
  std::vector<database::SceneConditions> selected;
  for (const auto& s : database::enumerateScenes(options.catalog)) {
    if (filter.matches(database::sceneIdOf(s, options.catalog), &s)) selected.push_back(s);
  }
  if (selected.empty()) throw py::value_error("scenes: the filter selects no scene");
  options.out = out;
  options.handFolder = data / "hands" / "sdh";
  options.materials = data / "materials.xml";
  options.threads = threads;
  options.seed = seed;
  try {
    options.camera = generator::findCameraProfile(camera, data / "cameras");
  } catch (const std::invalid_argument& e) {
    throw py::value_error(std::string("camera: ") + e.what());
  }
  std::mutex mutex;
  generator::GenerationProgress latest;
  bool fresh = false;
  const auto tick = [&] {
    generator::GenerationProgress p;
    {
      const std::lock_guard lock(mutex);
      if (!fresh) return;
      fresh = false;
      p = latest;
    }
    progress(p.done, p.total, p.lastId);
  };
  const generator::GenerationReport report = runInterruptible(
      [&](const std::atomic<bool>* stop) {
        options.stop = stop;
        return generator::generateDatabase(selected, options,
                                           [&](const generator::GenerationProgress& p) {
                                             const std::lock_guard lock(mutex);
                                             latest = p;
                                             fresh = true;
                                           });
      },
      progress.is_none() ? std::function<void()>() : std::function<void()>(tick));
  py::dict d;
  d["generated"] = report.generated;
  d["skipped"] = report.skipped;
  d["failures"] = report.failures;
  return d;
}

}  // namespace

void bindDatabase(py::module_& m) {
  py::class_<OpenDatabase>(m, "Database", R"doc(
A scene database opened for reading: a generated database folder (DIR/index.xml) or an original
VisGraB manifest (docs/database-format.md). Images and files are read when asked for.

    db = visgrab.Database("database")
    ids = db.scene_ids("plain/single/*")
    s = db.scene(ids[0])

Raises OSError (naming the file and line) when the index or manifest is missing or malformed.
)doc")
      .def(py::init([](const fs::path& path) {
             py::gil_scoped_release release;
             return OpenDatabase{
                 std::make_shared<const database::Database>(database::Database::openAny(path)),
                 path};
           }),
           py::arg("path"),
           "Opens a generated database folder (or its index.xml) or an original manifest file.")
      .def_property_readonly(
          "path", [](const OpenDatabase& d) { return d.path.string(); },
          "The path the database was opened from.")
      .def_property_readonly(
          "root", [](const OpenDatabase& d) { return d.db->root().string(); },
          "The database folder (generated) or the manifest's folder (original).")
      .def_property_readonly(
          "source",
          [](const OpenDatabase& d) {
            return d.db->source() == database::Database::Source::kGenerated ? "generated"
                                                                            : "original";
          },
          R"("generated" or "original" (an original VisGraB manifest).)")
      .def_property_readonly(
          "seed", [](const OpenDatabase& d) { return d.db->seed(); },
          "The generator's seed (0 for an original manifest).")
      .def_property_readonly(
          "warnings",
          [](const OpenDatabase& d) {
            std::vector<std::string> out;
            for (const auto& w : d.db->warnings()) out.push_back(w.format());
            return out;
          },
          "Warnings found while opening (file:line: warning: ...), as `visgrab db` prints them.")
      .def("scene_ids", &sceneIds, py::arg("filter") = py::none(),
           R"doc(The ids of the scenes `filter` selects, in database order.

`filter` is the CLI's --scenes syntax (docs/database-format.md, Filters): ',' AND, ';' OR, '!' NOT,
condition words (plain, textured, single, double, standing, lying, apart, close, an object name),
key=value terms and id globs, e.g. "plain,single,cocacola" or "textured/double/*". A list of
filters is their OR (a repeated --scenes). None or "" selects every scene.
Raises ValueError for a malformed filter (the message names the bad word).)doc")
      .def("scene", &sceneOf, py::arg("id"),
           "The scene with this id (ours or the original spelling). Raises ValueError for an "
           "unknown id, naming the closest known ids.")
      .def("__contains__",
           [](const OpenDatabase& d, const std::string& id) { return d.db->contains(id); })
      .def("__len__", [](const OpenDatabase& d) { return d.db->list().size(); })
      .def("__repr__", [](const OpenDatabase& d) {
        return "visgrab.Database(" + py::repr(py::cast(d.path.string())).cast<std::string>() +
               ", " + std::to_string(d.db->list().size()) + " scenes)";
      });

  py::class_<SceneView>(m, "Scene", R"doc(
One scene of a Database. Image properties read their file on each access (keep the array).
Frames: the world frame is the table frame (metres, z up); the point cloud, depth and mask are
in the rectified left camera's view (OpenCV axes: x right, y down, z forward), whose pose in
the table frame is `cloud_frame` (= calibration["X_table_camera"]).
)doc")
      .def_property_readonly(
          "id", [](const SceneView& s) { return s.entry.id; }, "The scene id.")
      .def_property_readonly(
          "original_id", [](const SceneView& s) { return s.entry.originalId; },
          "The id in the original VisGraB layout (e.g. textured/cocacola/img_03).")
      .def_property_readonly(
          "conditions",
          [](const SceneView& s) { return conditionsDict(s.entry.conditions, s.db->catalog()); },
          "dict: texture, kind, arrangement, objects (names), object_ids, pose, description; "
          "None when unknown (an original scene).")
      .def_property_readonly(
          "files", [](const SceneView& s) { return filesDict(s.entry); },
          "dict of the scene's files (paths; None where the scene has none), as `visgrab db "
          "show --json` lists them.")
      .def_property_readonly(
          "left",
          sceneImage(
              [](const database::Database& db, const std::string& id) { return db.leftImage(id); },
              [](const cv::Mat& image) { return rgbArray(image); }),
          "The rectified left image: HxWx3 uint8 in RGB order (not OpenCV's BGR).")
      .def_property_readonly("right",
                             sceneImage([](const database::Database& db,
                                           const std::string& id) { return db.rightImage(id); },
                                        [](const cv::Mat& image) { return rgbArray(image); }),
                             "The rectified right image: HxWx3 uint8 in RGB order.")
      .def_property_readonly(
          "raw_left", [](const SceneView& s) { return rawImage(s.entry.rawLeftImage); },
          "The raw left sensor image as stored (Bayer mosaic, distorted, unrectified; HxW "
          "uint8 or uint16), or None when the scene has none.")
      .def_property_readonly(
          "raw_right", [](const SceneView& s) { return rawImage(s.entry.rawRightImage); },
          "The raw right sensor image as stored, or None.")
      .def_property_readonly(
          "calibration",
          [](const SceneView& s) { return calibrationDict(s.db->calibration(s.entry.id)); },
          R"doc(The stereo calibration (calibration.yml) as a dict of numpy float64 arrays:
K1, K2 (3x3), D1, D2 (distortion, OpenCV order), R (3x3), T (3,), R1, R2 (3x3), P1, P2 (3x4),
Q (4x4), X_table_left (4x4: the raw left camera in the table frame), X_table_camera (4x4: the
rectified left camera, X_table_left R1^T, the frame of P1, Q, depth and the cloud), and width,
height (pixels), baseline (m). OpenCV conventions: x_right = R x_left + T.)doc")
      .def_property_readonly(
          "cloud_frame",
          [](const SceneView& s) {
            return matrixArray(s.db->calibration(s.entry.id).rectifiedLeftPose().matrix());
          },
          "4x4 pose of the point cloud's frame (the rectified left camera) in the table frame: "
          "p_table = cloud_frame @ [x, y, z, 1].")
      .def(
          "point_cloud",
          [](const SceneView& s, const std::string& frame) {
            if (frame != "camera" && frame != "table") {
              throw py::value_error(R"(frame must be "camera" or "table", got ")" + frame + "\"");
            }
            database::PointCloud cloud;
            Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
            {
              py::gil_scoped_release release;
              cloud = s.db->pointCloud(s.entry.id);
              if (frame == "table") X = s.db->calibration(s.entry.id).rectifiedLeftPose();
            }
            return cloudArray(cloud, X);
          },
          py::arg("frame") = "camera",
          R"doc(The scene's point cloud (cloud.ply) as an Nx6 float64 array: x y z (metres) and
r g b (0..255). frame="camera" (default): as stored, in the rectified left camera frame (see
cloud_frame); frame="table": moved into the table (world) frame.)doc")
      .def_property_readonly(
          "depth",
          sceneImage(
              [](const database::Database& db, const std::string& id) { return db.depthImage(id); },
              [](const cv::Mat& image) { return imageArray<float>(image); }),
          "Ground-truth depth of the rectified left view: HxW float32, camera z in metres, 0.0 "
          "where nothing was drawn (depth.png holds 0.1 mm units; this is that / 10000).")
      .def_property_readonly(
          "mask",
          sceneImage([](const database::Database& db,
                        const std::string& id) { return db.instanceMask(id); },
                     [](const cv::Mat& image) { return imageArray<std::uint8_t>(image); }),
          "Ground-truth instance mask of the rectified left view: HxW uint8, 0 background, 255 "
          "table, the object id (1..18) on object pixels.")
      .def_property_readonly(
          "disparity",
          sceneImage([](const database::Database& db,
                        const std::string& id) { return db.disparityImage(id); },
                     [](const cv::Mat& image) { return imageArray<float>(image); }),
          "The stereo matcher's disparity of the rectified pair: HxW float32 pixels, -1.0 where "
          "there is none.")
      .def_property_readonly(
          "ground_truth",
          [](const SceneView& s) {
            py::list out;
            for (const auto& o : s.db->groundTruth(s.entry.id)) {
              py::dict d;
              d["object"] = o.object;
              d["name"] = std::string(s.db->catalog().name(o.object));
              d["pose"] = matrixArray(o.X_WO.matrix());
              out.append(d);
            }
            return out;
          },
          "The objects' true poses: a list of dicts (object id, name, pose: 4x4 in the table "
          "frame); empty for original scenes.")
      .def("__repr__", [](const SceneView& s) {
        return "visgrab.Scene(" + py::repr(py::cast(s.entry.id)).cast<std::string>() + ")";
      });

  m.def("_generate_database", &generate, py::arg("out"), py::arg("scenes"), py::arg("threads"),
        py::arg("camera"), py::arg("seed"), py::arg("data"), py::arg("objects"),
        py::arg("progress"),
        "generate_database's C++ side (visgrab.generate_database documents it).");
}

}  // namespace visgrab::python
