// Contact generation (rwsim::contacts::collide) for the pairs a grasp simulation meets every
// 5 ms step: a box and a can resting, a fingertip hull pressing a box, a hull on a non-convex
// object mesh. RobWork's SDH fingertip hull and GreenCup mesh are used when RW_COMPAT_DATA is
// set, otherwise convex and non-convex meshes of similar size made here. With RW_COMPAT_DATA,
// also ContactDetector::detect on RobWork's SDH test scene (27 hull pairs). And detect() as the
// main job calls it: every step of a grasp trial of the project's SDH around an object of a
// two-object database scene ($VISGRAB_BENCH_DB, else the scene generated at start-up).
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <numbers>
#include <vector>

#include "bench_database.hpp"
#include "rw/geometry/mesh_loader.hpp"
#include "rw/kinematics/frame_tree.hpp"
#include "rw/math/rpy.hpp"
#include "rwsim/contacts/contact_detector.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/simulator/grasp_trial.hpp"

namespace {

using rw::geometry::Geometry;
using rw::geometry::TriMesh;
using rw::math::Transform3D;
using rw::math::Vector3D;
using rwsim::contacts::ContactOptions;
using rwsim::contacts::ContactPoint;
using rwsim::contacts::ContactShape;

constexpr double kPen = 1e-4;

Transform3D pose(const Vector3D& p, double angle = 0.0, const Vector3D& axis = Vector3D::UnitZ()) {
  Transform3D X = Transform3D::Identity();
  X.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  X.translation() = p;
  return X;
}

/// A closed cylinder mesh with `segments` sides: 4 * segments triangles.
std::shared_ptr<const Geometry> fineCylinder(double r, double h, std::uint32_t segments) {
  auto m = std::make_shared<TriMesh>();
  for (const double z : {-h / 2, h / 2}) {
    for (std::uint32_t i = 0; i < segments; ++i) {
      const double a = 2.0 * std::numbers::pi * i / segments;
      m->vertices.emplace_back(r * std::cos(a), r * std::sin(a), z);
    }
  }
  const auto bottom = static_cast<std::uint32_t>(m->vertices.size());
  m->vertices.emplace_back(0, 0, -h / 2);
  m->vertices.emplace_back(0, 0, h / 2);
  for (std::uint32_t i = 0; i < segments; ++i) {
    const std::uint32_t j = (i + 1) % segments;
    m->triangles.push_back({i, j, segments + j});
    m->triangles.push_back({i, segments + j, segments + i});
    m->triangles.push_back({bottom, j, i});
    m->triangles.push_back({bottom + 1, segments + i, segments + j});
  }
  return Geometry::mesh(m, "fine_cylinder");
}

/// A non-convex closed mesh: a cylinder whose side bulges and dents (a wavy can), about 8k
/// triangles.
std::shared_ptr<const Geometry> wavyCan(double r, double h) {
  constexpr std::uint32_t kSegments = 64;
  constexpr std::uint32_t kRings = 64;
  auto m = std::make_shared<TriMesh>();
  for (std::uint32_t k = 0; k <= kRings; ++k) {
    const double z = -h / 2 + h * k / kRings;
    for (std::uint32_t i = 0; i < kSegments; ++i) {
      const double a = 2.0 * std::numbers::pi * i / kSegments;
      const double radius =
          r * (1.0 + 0.05 * std::sin(6 * a) * std::sin(std::numbers::pi * k / kRings));
      m->vertices.emplace_back(radius * std::cos(a), radius * std::sin(a), z);
    }
  }
  const auto at = [](std::uint32_t k, std::uint32_t i) { return k * kSegments + i % kSegments; };
  const auto bottom = static_cast<std::uint32_t>(m->vertices.size());
  m->vertices.emplace_back(0, 0, -h / 2);
  m->vertices.emplace_back(0, 0, h / 2);
  for (std::uint32_t i = 0; i < kSegments; ++i) {
    for (std::uint32_t k = 0; k < kRings; ++k) {
      m->triangles.push_back({at(k, i), at(k, i + 1), at(k + 1, i + 1)});
      m->triangles.push_back({at(k, i), at(k + 1, i + 1), at(k + 1, i)});
    }
    m->triangles.push_back({bottom, at(0, i + 1), at(0, i)});
    m->triangles.push_back({bottom + 1, at(kRings, i), at(kRings, i + 1)});
  }
  return Geometry::mesh(m, "wavy_can");
}

std::shared_ptr<const Geometry> compatMesh(const char* relative) {
  const char* dir = std::getenv("RW_COMPAT_DATA");
  if (dir == nullptr) return nullptr;
  const std::filesystem::path file = std::filesystem::path(dir) / relative;
  if (!std::filesystem::exists(file)) return nullptr;
  return Geometry::mesh(rw::geometry::loadMesh(file), file.string());
}

/// Pose putting `g`'s lowest vertex (after rotation X) kPen below `target`.
Transform3D restingPose(const Geometry& g, Transform3D X,
                        const Vector3D& target = Vector3D::Zero()) {
  Vector3D lowest = Vector3D::Constant(std::numeric_limits<double>::infinity());
  for (const Vector3D& v : g.triangles().vertices) {
    if ((X * v).z() < lowest.z()) lowest = X * v;
  }
  X.translation() += target - lowest - Vector3D(0, 0, kPen);
  return X;
}

void runPair(benchmark::State& state, const Geometry& a, const Transform3D& X_a, const Geometry& b,
             const Transform3D& X_b) {
  const auto sa = ContactShape::build(a);
  const auto sb = ContactShape::build(b);
  const ContactOptions options;
  std::vector<ContactPoint> out;
  for (auto _ : state) {
    out.clear();
    rwsim::contacts::collide(*sa, X_a, *sb, X_b, options, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["points"] = static_cast<double>(out.size());
}

void BM_Contacts_BoxOnPlane(benchmark::State& state) {
  runPair(state, *Geometry::plane(), pose({0, 0, 0}), *Geometry::box(0.1, 0.06, 0.04),
          pose({0.1, 0.2, 0.02 - kPen}, 0.3));
}
BENCHMARK(BM_Contacts_BoxOnPlane);

void BM_Contacts_BoxOnBox(benchmark::State& state) {
  const auto box = Geometry::box(0.1, 0.1, 0.1);
  runPair(state, *Geometry::box(1, 1, 0.1), pose({0, 0, -0.05}), *box,
          pose({0.1, 0, 0.05 - kPen}, 0.5));
}
BENCHMARK(BM_Contacts_BoxOnBox);

void BM_Contacts_SphereOnBox(benchmark::State& state) {
  runPair(state, *Geometry::box(1, 1, 0.1), pose({0, 0, -0.05}), *Geometry::sphere(0.03),
          pose({0.1, 0, 0.03 - kPen}));
}
BENCHMARK(BM_Contacts_SphereOnBox);

void BM_Contacts_CylinderOnBox(benchmark::State& state) {
  runPair(state, *Geometry::box(1, 1, 0.1), pose({0, 0, -0.05}), *Geometry::cylinder(0.03, 0.1),
          pose({0.1, 0, 0.05 - kPen}, 0.2));
}
BENCHMARK(BM_Contacts_CylinderOnBox);

void BM_Contacts_HullOnBox(benchmark::State& state) {
  auto hull = compatMesh("devices/SDH2/geometry/FingerTip_hull.stl");
  state.SetLabel(hull ? "SDH2 FingerTip_hull (1376 triangles)" : "cylinder mesh (1200 triangles)");
  if (!hull) hull = fineCylinder(0.01, 0.03, 300);
  const auto box = Geometry::box(0.2, 0.2, 0.1);
  const Transform3D X = restingPose(*hull, pose({0.01, -0.02, 0}, 1.9, Vector3D(1, 0.3, 0.2)));
  runPair(state, *box, pose({0, 0, -0.05}), *hull, X);
}
BENCHMARK(BM_Contacts_HullOnBox);

void BM_Contacts_HullOnMesh(benchmark::State& state) {
  auto hull = compatMesh("devices/SDH2/geometry/FingerTip_hull.stl");
  auto object = compatMesh("objects/GreenCup_5k_tex.stl");
  state.SetLabel(object ? "SDH2 FingerTip_hull on GreenCup" : "cylinder mesh on wavy can");
  if (!hull) hull = fineCylinder(0.01, 0.03, 300);
  if (!object) object = wavyCan(0.04, 0.12);
  // The object lies on its side; the tip presses its topmost vertex.
  const Transform3D X_object = pose({0, 0, 0}, std::numbers::pi / 2, Vector3D::UnitX());
  Vector3D top = Vector3D::Constant(-std::numeric_limits<double>::infinity());
  for (const Vector3D& v : object->triangles().vertices) {
    if ((X_object * v).z() > top.z()) top = X_object * v;
  }
  const Transform3D X = restingPose(*hull, pose({0, 0, 0}, 1.9, Vector3D(1, 0.3, 0.2)), top);
  runPair(state, *object, X_object, *hull, X);
}
BENCHMARK(BM_Contacts_HullOnMesh);

/// Body pairs joined by a joint (a body and the nearest body above its frame), which the
/// simulator leaves out: their hulls overlap at the joint.
std::vector<std::pair<rwsim::dynamics::BodyId, rwsim::dynamics::BodyId>> jointConnected(
    const rwsim::dynamics::DynamicWorkCell& dwc) {
  std::vector<std::pair<rwsim::dynamics::BodyId, rwsim::dynamics::BodyId>> pairs;
  const auto& tree = dwc.workcell().frames();
  for (std::size_t i = 0; i < dwc.bodies().size(); ++i) {
    const rwsim::dynamics::BodyId b(i);
    for (auto f = tree.frame(dwc.body(b).frame).parent(); f.valid(); f = tree.frame(f).parent()) {
      const rwsim::dynamics::BodyId owner = dwc.bodyOfFrame(f);
      if (!owner.valid() || owner == b) continue;
      pairs.emplace_back(owner, b);
      break;
    }
  }
  return pairs;
}

void BM_Contacts_SdhSceneDetect(benchmark::State& state) {
  const char* dir = std::getenv("RW_COMPAT_DATA");
  if (dir == nullptr) {
    state.SkipWithError("RW_COMPAT_DATA is not set (RobWork's SDH test scene is needed)");
    return;
  }
  const auto dwc = rwsim::loaders::loadDynamicWorkCell(std::filesystem::path(dir) /
                                                       "devices/SDH2/test_scene.dwc.xml");
  const rwsim::contacts::ContactDetector detector(*dwc, {}, jointConnected(*dwc));
  const auto& wc = dwc->workcell();
  const rw::kinematics::FKTable fk(wc.frames(), wc.defaultState());
  std::vector<Transform3D> poses;
  for (const auto& body : dwc->bodies()) poses.push_back(fk.worldTransform(body.frame));
  std::vector<rwsim::contacts::BodyContact> out;
  for (auto _ : state) {
    detector.detect(poses, out);
    benchmark::DoNotOptimize(out.data());
  }
  state.counters["pairs"] = static_cast<double>(detector.candidatePairs().size());
  state.counters["touching"] = static_cast<double>(out.size());
}
BENCHMARK(BM_Contacts_SdhSceneDetect);

/// The database scene of BM_Contacts_DatabaseTrialDetect: two standing cans side by side.
constexpr const char* kTrialScene = "plain/double/cocacola_saltcylinder/01";

/// Body poses at every step of one grasp trial in kTrialScene (the SDH with the SDH_CYL
/// pre-shape pointing down at the first object, its TCP at the centre of the object's box or
/// the lowest centimetre above it where the open hand is clear), with the scene's dwc.
struct RecordedTrial {
  std::unique_ptr<rwsim::dynamics::DynamicWorkCell> dwc;
  std::vector<std::vector<Transform3D>> steps;
  std::string outcome;
};

const RecordedTrial& recordedTrial() {
  static const RecordedTrial trial = [] {
    namespace sim = rwsim::simulator;
    const visgrab::bench::BenchDatabase database({kTrialScene});
    RecordedTrial out;
    out.dwc = rwsim::loaders::loadDynamicWorkCell(database.db().scene(kTrialScene).dynamicWorkcell);
    const auto& dwc = *out.dwc;
    const auto& wc = dwc.workcell();
    const rw::kinematics::FKTable fk(wc.frames(), wc.defaultState());
    // The first rigid body that is not part of the hand: the first object.
    rw::geometry::Aabb box;
    for (const auto& body : dwc.bodies()) {
      if (body.kind != rwsim::dynamics::BodyKind::kRigid ||
          wc.frames().frame(body.frame).name().starts_with("SchunkHand")) {
        continue;
      }
      for (const auto frame : body.geometryFrames) {
        const auto* object = wc.findObject(frame);
        if (object == nullptr) continue;
        for (const auto& g : object->collision) {
          const Transform3D X = fk.worldTransform(frame) * g.X_frame_geometry;
          for (const Vector3D& v : g.geometry->triangles().vertices) box.extend(X * v);
        }
      }
      break;
    }
    sim::GraspTrialSetup setup;
    setup.hand = "SchunkHand";
    setup.tcpFrame = "SchunkHand.SDHTCP";
    setup.simulator = sim::optionsFromEngineProperties(dwc);
    setup.computeGws = false;
    setup.observer = [&out, &dwc](const rwsim::trial::PhysicsEngine& simulator, std::string_view) {
      std::vector<Transform3D> poses;
      for (std::size_t i = 0; i < dwc.bodies().size(); ++i) {
        poses.push_back(simulator.bodyPose(rwsim::dynamics::BodyId(i)));
      }
      out.steps.push_back(std::move(poses));
    };
    const sim::GraspTrial grasp(dwc, setup);
    sim::GraspParameters g;
    g.qOpen = rw::math::Q(7);
    g.qOpen << -1.048, 0.174, 0.0, -1.048, 0.174, -1.048, 0.174;
    g.qClosed = rw::math::Q(7);
    g.qClosed << 0.0, 0.349, 0.0, 0.0, 0.349, 0.0, 0.349;
    g.tauMax = rw::math::Q(7);
    g.tauMax << 2.1, 1.4, 2.1, 1.05, 0.7, 1.05, 0.7;
    // The TCP at the box's centre, raised by centimetres until the open hand is clear of it.
    const Vector3D centre = 0.5 * (box.min + box.max);
    for (int cm = 0; cm <= 20; ++cm) {
      g.X_W_tcp = rw::math::rpyTransform(Vector3D(0, std::numbers::pi, 0),
                                         centre + Vector3D(0, 0, 0.01 * cm));
      if (!grasp.checkPlacement(g, wc.defaultState()).collides) break;
    }
    out.outcome = std::string(sim::outcomeName(grasp.run(g, wc.defaultState()).outcome));
    return out;
  }();
  return trial;
}

void BM_Contacts_DatabaseTrialDetect(benchmark::State& state) {
  const RecordedTrial& trial = recordedTrial();
  if (trial.steps.empty()) {
    state.SkipWithError(
        ("the trial in " + std::string(kTrialScene) + " took no step (" + trial.outcome + ")")
            .c_str());
    return;
  }
  const rwsim::contacts::ContactDetector detector(
      *trial.dwc, rwsim::simulator::optionsFromEngineProperties(*trial.dwc).contacts,
      rwsim::dynamics::jointConnectedBodyPairs(*trial.dwc));
  std::vector<rwsim::contacts::BodyContact> out;
  std::size_t step = 0;
  std::int64_t points = 0;
  std::int64_t calls = 0;
  for (auto _ : state) {
    detector.detect(trial.steps[step], out);
    benchmark::DoNotOptimize(out.data());
    for (const auto& c : out) points += static_cast<std::int64_t>(c.points.size());
    ++calls;
    step = step + 1 == trial.steps.size() ? 0 : step + 1;
  }
  state.SetLabel(std::string(kTrialScene) + ", " + std::to_string(trial.steps.size()) + " steps, " +
                 trial.outcome);
  state.counters["pairs"] = static_cast<double>(detector.candidatePairs().size());
  state.counters["points/step"] = static_cast<double>(points) / static_cast<double>(calls);
}
BENCHMARK(BM_Contacts_DatabaseTrialDetect)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
