#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <string>
#include <vector>

#include "cli_common/data_folder.hpp"
#include "common.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/taskio/grasp_file.hpp"
#include "visgrab/taskio/grasp_list.hpp"

namespace visgrab::python {

namespace {

namespace fs = std::filesystem;
using grasp::GraspKind;
using grasp::GraspRequest;

py::array_t<double> vectorOf(const Eigen::VectorXd& v) {
  py::array_t<double> out(static_cast<py::ssize_t>(v.size()));
  auto view = out.mutable_unchecked<1>();
  for (Eigen::Index i = 0; i < v.size(); ++i) view(i) = v(i);
  return out;
}

py::array_t<double> poseOf(const rw::math::Transform3D& X) {
  py::array_t<double> out({py::ssize_t{4}, py::ssize_t{4}});
  auto view = out.mutable_unchecked<2>();
  const auto& m = X.matrix();
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) view(r, c) = m(r, c);
  }
  return out;
}

// The rotation as a unit quaternion [w, x, y, z] with w >= 0 (as the grasp list writes it).
Eigen::Vector4d quaternionOf(const rw::math::Transform3D& X) {
  Eigen::Quaterniond q(X.linear());
  q.normalize();
  if (q.w() < 0.0) q.coeffs() *= -1.0;
  return {q.w(), q.x(), q.y(), q.z()};
}

bool hasPose(const GraspRequest& g) {
  return g.kind != GraspKind::kContacts && g.kind != GraspKind::kJaw;
}

// One number in a Python literal (repr of a float: shortest round trip).
std::string number(double v) { return py::repr(py::float_(v)).cast<std::string>(); }

std::string listText(const Eigen::VectorXd& v) {
  std::string out = "[";
  for (Eigen::Index i = 0; i < v.size(); ++i) out += (i > 0 ? ", " : "") + number(v(i));
  return out + "]";
}

std::string quoted(const std::string& s) { return py::repr(py::str(s)).cast<std::string>(); }

std::string graspRepr(const GraspRequest& g) {
  std::string out = "visgrab.Grasp." + std::string(grasp::kindName(g.kind)) +
                    "(scene=" + quoted(g.sceneId) + ", method=" + quoted(g.method) +
                    ", id=" + quoted(g.id);
  if (hasPose(g)) {
    out += ", position=" + listText(g.X_W_tcp.translation()) +
           ", quaternion=" + listText(quaternionOf(g.X_W_tcp));
  }
  switch (g.kind) {
    case GraspKind::kPreshape:
      out += ", preshape=" + quoted(g.preshape);
      break;
    case GraspKind::kPoseAndQ:
      out += ", q=" + listText(g.qOpen);
      break;
    case GraspKind::kRaw:
      out += ", q_open=" + listText(g.qOpen) + ", q_closed=" + listText(g.qClosed) +
             ", tau_max=" + listText(g.tauMax);
      break;
    case GraspKind::kContacts: {
      out += ", contacts=[";
      for (std::size_t i = 0; i < g.contacts.size(); ++i) {
        Eigen::VectorXd c(6);
        c << g.contacts[i].position, g.contacts[i].direction;
        out += (i > 0 ? ", " : "") + listText(c);
      }
      out += "], approach=" + listText(g.approach);
      break;
    }
    case GraspKind::kJaw:
      out += ", position=" + listText(g.X_W_jaw.translation()) +
             ", quaternion=" + listText(quaternionOf(g.X_W_jaw)) + ", width=" + number(g.width);
      if (g.score) out += ", score=" + number(*g.score);
      break;
  }
  return out + ")";
}

// One grasp list line parsed by the grasp list reader: its rules and messages are the CLI's.
GraspRequest graspFromLine(const std::string& line, const std::string& origin) {
  taskio::GraspFileContents read = taskio::parseGraspList(line, origin);
  if (!read.rejected.empty()) throw py::value_error(origin + ": " + read.rejected.front().message);
  if (read.requests.size() != 1) {
    throw py::value_error(origin + ": expected one grasp, got " +
                          std::to_string(read.requests.size()));
  }
  GraspRequest g = std::move(read.requests.front());
  g.sourceFile.clear();
  g.sourceLine = 0;
  return g;
}

// Hand(name|folder|file): the grasp description file it names (cli::handPath's rules).
fs::path findHand(const std::string& text, const fs::path& data) {
  const fs::path path = cli::handPath(text, data);
  std::error_code error;
  if (!fs::exists(path, error)) {
    throw rw::common::LoadError({rw::common::Diagnostic{
        rw::common::Diagnostic::Severity::kError, text, 0, 0, "no such file or folder", {}}});
  }
  return grasp::graspDescriptionFile(path);
}

py::dict preshapeDict(const grasp::PreShape& p) {
  py::dict d;
  d["name"] = p.name;
  d["aliases"] = p.aliases;
  d["q_open"] = vectorOf(p.qOpen);
  d["q_closed"] = vectorOf(p.qClosed);
  d["tau_max"] = vectorOf(p.tauMax);
  return d;
}

}  // namespace

void bindGrasps(py::module_& m) {
  py::class_<Hand>(m, "Hand", R"doc(
A hand's grasp description (scenes/hands/README.md) and its kinematic model, loaded once.

    visgrab.Hand("sdh")                            # a hand of the data folder by name
    visgrab.Hand("scenes/hands/pg70")              # a hand's folder
    visgrab.Hand("my/hand.grasp.xml")              # a grasp description file

Names are looked up in DATA/hands, where DATA is $VISGRAB_DATA, else the installed
share/visgrab/scenes, else the source tree's scenes/ (as the `visgrab` program does).
Raises ValueError for an unknown name, OSError (file:line:column) for a missing or invalid file.
)doc")
      .def(py::init([](const py::object& hand) {
             // Names are looked up in visgrab.data_folder() (the package's Python side).
             const auto data =
                 py::module_::import("visgrab").attr("data_folder")().cast<fs::path>();
             const fs::path file = findHand(py::str(hand).cast<std::string>(), data);
             py::gil_scoped_release release;
             return Hand{
                 std::shared_ptr<const grasp::HandGraspSetup>(grasp::loadHandGraspSetup(file)),
                 fs::absolute(file).lexically_normal()};
           }),
           py::arg("hand") = "sdh",
           "Loads a hand: a name in DATA/hands (\"sdh\", \"pg70\", ...), a hand's folder or a "
           "*.grasp.xml file.")
      .def_property_readonly(
          "name", [](const Hand& h) { return h.setup->deviceName(); },
          "The hand's device name (e.g. SchunkHand).")
      .def_property_readonly(
          "dof", [](const Hand& h) { return h.setup->dof(); }, "Degrees of freedom.")
      .def_property_readonly(
          "file", [](const Hand& h) { return h.file.string(); },
          "The grasp description file (*.grasp.xml).")
      .def_property_readonly(
          "workcell_file", [](const Hand& h) { return h.setup->workcellFile().string(); },
          "The hand's workcell file.")
      .def_property_readonly(
          "controller", [](const Hand& h) { return h.setup->controllerName(); },
          "The controller's name.")
      .def_property_readonly(
          "tcp_frame", [](const Hand& h) { return h.setup->tcpFrameName(); },
          "The TCP frame: grasp poses are poses of this frame in the table frame.")
      .def_property_readonly(
          "jaw_frame",
          [](const Hand& h) -> py::object {
            const grasp::JawFrame* jaw = h.setup->jawFrame();
            if (jaw == nullptr) return py::none();
            py::dict d;
            d["X_tcp_jaw"] = poseOf(jaw->X_tcp_jaw);
            d["stroke"] = jaw->stroke;
            d["tip_depth"] = jaw->tipDepth;
            d["preshape"] = h.setup->preshapes()[jaw->preshape].name;
            return d;
          },
          "The hand's parallel-jaw frame (docs/grasp-format.md, \"Parallel-jaw grasps\"): dict "
          "X_tcp_jaw (4x4), stroke (m), tip_depth (pad centre to the fingertips' front, m), "
          "preshape; None when the hand declares none.")
      .def_property_readonly(
          "preshapes",
          [](const Hand& h) {
            std::vector<std::string> names;
            for (const auto& p : h.setup->preshapes()) names.push_back(p.name);
            return names;
          },
          "The pre-shape names, in file order (list[str]).")
      .def(
          "preshape",
          [](const Hand& h, const std::string& name) {
            const grasp::PreShape* p = h.setup->findPreshape(name);
            if (p == nullptr) {
              std::string known;
              for (const auto& s : h.setup->preshapes())
                known += (known.empty() ? "" : ", ") + s.name;
              throw py::value_error("unknown pre-shape \"" + name + "\" for hand \"" +
                                    h.setup->deviceName() + "\" (known: " + known + ")");
            }
            return preshapeDict(*p);
          },
          py::arg("name"),
          "The pre-shape with this name or alias: dict name, aliases, q_open, q_closed, tau_max "
          "(numpy arrays, one value per DOF). Raises ValueError for an unknown name.")
      .def("__repr__", [](const Hand& h) {
        return "visgrab.Hand(" + quoted(h.setup->deviceName()) +
               ", dof=" + std::to_string(h.setup->dof()) + ", file=" + quoted(h.file.string()) +
               ")";
      });

  py::class_<Grasp>(m, "Grasp", R"doc(
One grasp hypothesis for one scene, as a line of the grasp list (docs/grasp-format.md). Make one
with Grasp.preshape, Grasp.pose_q, Grasp.raw, Grasp.contacts or Grasp.jaw; the values are checked by the
grasp list's own reader (the CLI's rules and messages: ValueError on a bad value). Poses are
the hand's TCP frame in the table (world) frame, metres; quaternions [w, x, y, z] (unit). A jaw
grasp (Grasp.jaw, visgrab.import_grasps) gives the jaw frame's pose instead (jaw_pose), placed
through the hand's declared jaw frame.
)doc")
      .def_property_readonly(
          "scene", [](const Grasp& g) { return g.request.sceneId; }, "The scene id.")
      .def_property_readonly(
          "method", [](const Grasp& g) { return g.request.method; },
          "The method's name (the analyses group by it).")
      .def_property_readonly(
          "id", [](const Grasp& g) { return g.request.id; },
          "The grasp id, unique per (scene, method).")
      .def_property_readonly(
          "kind", [](const Grasp& g) { return std::string(grasp::kindName(g.request.kind)); },
          R"("preshape", "pose_q", "raw", "contacts" or "jaw".)")
      .def_property_readonly(
          "position",
          [](const Grasp& g) -> py::object {
            if (!hasPose(g.request)) return py::none();
            return vectorOf(g.request.X_W_tcp.translation());
          },
          "The TCP position (3,), metres; None for a contacts grasp.")
      .def_property_readonly(
          "quaternion",
          [](const Grasp& g) -> py::object {
            if (!hasPose(g.request)) return py::none();
            return vectorOf(quaternionOf(g.request.X_W_tcp));
          },
          "The TCP rotation as a unit quaternion [w, x, y, z] with w >= 0; None for contacts.")
      .def_property_readonly(
          "pose",
          [](const Grasp& g) -> py::object {
            if (!hasPose(g.request)) return py::none();
            return poseOf(g.request.X_W_tcp);
          },
          "The TCP pose as a 4x4 matrix in the table frame; None for a contacts grasp.")
      .def_property_readonly(
          "preshape",
          [](const Grasp& g) -> py::object {
            if (g.request.kind != GraspKind::kPreshape) return py::none();
            return py::str(g.request.preshape);
          },
          "The pre-shape's name (preshape grasps), else None.")
      .def_property_readonly(
          "q",
          [](const Grasp& g) -> py::object {
            if (g.request.kind != GraspKind::kPoseAndQ) return py::none();
            return vectorOf(g.request.qOpen);
          },
          "The configuration q (pose_q grasps), else None.")
      .def_property_readonly(
          "q_open",
          [](const Grasp& g) -> py::object {
            if (g.request.kind != GraspKind::kRaw) return py::none();
            return vectorOf(g.request.qOpen);
          },
          "The configuration when placed (raw grasps), else None.")
      .def_property_readonly(
          "q_closed",
          [](const Grasp& g) -> py::object {
            if (g.request.kind != GraspKind::kRaw) return py::none();
            return vectorOf(g.request.qClosed);
          },
          "The configuration the fingers close towards (raw grasps), else None.")
      .def_property_readonly(
          "tau_max",
          [](const Grasp& g) -> py::object {
            if (g.request.kind != GraspKind::kRaw) return py::none();
            return vectorOf(g.request.tauMax);
          },
          "The torque limits (raw grasps; empty: the hand's rule), else None.")
      .def_property_readonly(
          "contacts",
          [](const Grasp& g) -> py::object {
            if (g.request.kind != GraspKind::kContacts) return py::none();
            const auto n = static_cast<py::ssize_t>(g.request.contacts.size());
            py::array_t<double> out({n, py::ssize_t{6}});
            auto view = out.mutable_unchecked<2>();
            for (py::ssize_t i = 0; i < n; ++i) {
              const auto& c = g.request.contacts[static_cast<std::size_t>(i)];
              for (int k = 0; k < 3; ++k) {
                view(i, k) = c.position(k);
                view(i, 3 + k) = c.direction(k);
              }
            }
            return out;
          },
          "The desired contacts (contacts grasps) as a (c, 6) array of point (m) and push "
          "direction rows, else None.")
      .def_property_readonly(
          "approach",
          [](const Grasp& g) -> py::object {
            if (g.request.kind != GraspKind::kContacts) return py::none();
            return vectorOf(g.request.approach);
          },
          "The approach direction (contacts grasps), else None.")
      .def_property_readonly(
          "width",
          [](const Grasp& g) -> py::object {
            if (g.request.kind != GraspKind::kJaw) return py::none();
            return py::float_(g.request.width);
          },
          "The opening between the pads the grasp needs, m (jaw grasps), else None.")
      .def_property_readonly(
          "score",
          [](const Grasp& g) -> py::object {
            if (!g.request.score) return py::none();
            return py::float_(*g.request.score);
          },
          "The method's score of the grasp (imported grasps keep it), else None.")
      .def_property_readonly(
          "jaw_pose",
          [](const Grasp& g) -> py::object {
            if (g.request.kind != GraspKind::kJaw) return py::none();
            return poseOf(g.request.X_W_jaw);
          },
          "The jaw frame's pose as a 4x4 matrix in the table frame (jaw grasps: origin between "
          "the pads, z the approach, x the closing axis), else None.")
      .def_property_readonly(
          "jaw_position",
          [](const Grasp& g) -> py::object {
            if (g.request.kind != GraspKind::kJaw) return py::none();
            return vectorOf(g.request.X_W_jaw.translation());
          },
          "The jaw frame's origin (3,), metres (jaw grasps), else None.")
      .def_property_readonly(
          "jaw_quaternion",
          [](const Grasp& g) -> py::object {
            if (g.request.kind != GraspKind::kJaw) return py::none();
            return vectorOf(quaternionOf(g.request.X_W_jaw));
          },
          "The jaw frame's rotation [w, x, y, z], w >= 0 (jaw grasps), else None.")
      .def("__repr__", [](const Grasp& g) { return graspRepr(g.request); })
      .def("__eq__",
           [](const Grasp& a, const Grasp& b) {
             return taskio::formatGraspList({a.request}) == taskio::formatGraspList({b.request});
           })
      .def_static(
          "_from_line",
          [](const std::string& line, const std::string& origin) {
            return Grasp{graspFromLine(line, origin)};
          },
          py::arg("line"), py::arg("origin"),
          "A grasp from one grasp list line, checked by the grasp list reader.");

  m.def(
      "_write_grasps",
      [](const fs::path& file, const std::vector<Grasp>& grasps) {
        std::vector<GraspRequest> requests;
        requests.reserve(grasps.size());
        for (const auto& g : grasps) requests.push_back(g.request);
        try {
          taskio::writeGraspList(requests, file);
        } catch (const std::invalid_argument&) {
          throw;
        } catch (const std::runtime_error& e) {
          throw OsError(e.what());
        }
      },
      py::arg("path"), py::arg("grasps"), "write_grasps's C++ side.");

  m.def(
      "_read_grasps",
      [](const fs::path& path) {
        taskio::GraspFileContents read;
        {
          py::gil_scoped_release release;
          read = taskio::readGraspSources({path});
        }
        std::vector<Grasp> grasps;
        for (auto& r : read.requests) grasps.push_back(Grasp{std::move(r)});
        std::vector<std::string> rejected;
        for (const auto& d : read.rejected) rejected.push_back(d.format());
        std::vector<std::string> warnings;
        for (const auto& d : read.warnings) warnings.push_back(d.format());
        return py::make_tuple(grasps, rejected, warnings);
      },
      py::arg("path"), "read_grasps's C++ side: (grasps, rejected, warnings).");
}

}  // namespace visgrab::python
