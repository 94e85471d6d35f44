#include "sim_commands.hpp"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <string>

#include "json_writer.hpp"
#include "protocol_option.hpp"
#include "rw/common/diagnostic.hpp"
#include "rw/math/rpy.hpp"
#include "rwsim/engines/engine_registry.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "rwsim/simulator/simulator.hpp"
#include "visgrab/database/database.hpp"
#include "visgrab/grasp/grasp_resolver.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"
#include "visgrab/results/csv.hpp"
#include "visgrab/session/scene_loader.hpp"

namespace visgrab::app {

namespace {

using rw::math::Transform3D;
using rwsim::dynamics::DynamicWorkCell;

std::string fmt(double v, int precision = 6) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", precision, v);
  return buf;
}

std::string vectorText(const Eigen::VectorXd& v, int precision = 6) {
  std::string out;
  for (Eigen::Index i = 0; i < v.size(); ++i) out += (i ? " " : "") + fmt(v[i], precision);
  return out;
}

// Loads a dynamic workcell, printing warnings; nullptr (after printing the errors) on failure.
std::unique_ptr<DynamicWorkCell> load(const std::string& file) {
  std::vector<rw::common::Diagnostic> warnings;
  try {
    auto dwc = rwsim::loaders::loadDynamicWorkCell(file, &warnings);
    for (const auto& w : warnings) std::cerr << w.format() << "\n";
    return dwc;
  } catch (const rw::common::LoadError& e) {
    for (const auto& w : warnings) std::cerr << w.format() << "\n";
    std::cerr << e.what() << "\n";
    return nullptr;
  }
}

double positiveOption(const Arguments& a, const std::string& name, std::optional<double> def) {
  const auto text = a.option(name);
  if (!text) {
    if (!def) throw UsageError("--" + name + " is required");
    return *def;
  }
  const double v = parseNumber(name, *text);
  if (!(v > 0.0)) throw UsageError("--" + name + " must be > 0, got " + *text);
  return v;
}

// The options that carry several numbers (`--pose x y z r p y`, also `--pose=x,y,...` or one
// quoted word), by name; each may be given once.
std::map<std::string, std::vector<double>> numberLists(const Arguments& a,
                                                       const std::vector<std::string>& names) {
  std::map<std::string, std::vector<double>> lists;
  for (const auto& name : names) {
    const auto given = a.occurrences(name);
    if (given.empty()) continue;
    if (given.size() > 1) throw UsageError("--" + name + " given twice");
    auto& values = lists[name];
    for (const auto& word : given.front()) {
      std::istringstream is(word);
      for (std::string w; is >> w;) values.push_back(parseNumber(name, w));
    }
    if (values.empty()) throw UsageError("--" + name + " needs numbers");
  }
  return lists;
}

// --- visgrab sim --------------------------------------------------------------------------

void writePoseRow(std::ostream& out, double t, const std::string& body, const Transform3D& X) {
  const Eigen::Quaterniond q(X.linear());
  const auto& p = X.translation();
  out << fmt(t, 9) << "," << results::csvField(body) << "," << fmt(p.x(), 9) << "," << fmt(p.y(), 9)
      << "," << fmt(p.z(), 9) << "," << fmt(q.w(), 9) << "," << fmt(q.x(), 9) << ","
      << fmt(q.y(), 9) << "," << fmt(q.z(), 9) << "\n"
      << std::flush;
}

int runSim(const Arguments& a) {
  const double duration = positiveOption(a, "time", std::nullopt);
  const auto dwc = load(a.positionals()[0]);
  if (!dwc) return 1;
  auto options = rwsim::simulator::optionsFromEngineProperties(*dwc);
  options.timeStep = positiveOption(a, "dt", options.timeStep);
  std::ofstream file;
  if (const auto out = a.option("out")) {
    file.open(*out);
    if (!file) {
      std::cerr << "visgrab sim: cannot write " << *out << "\n";
      return 1;
    }
    file << "time,body,x,y,z,qw,qx,qy,qz\n" << std::flush;
  }
  rwsim::simulator::Simulator sim(*dwc, options);
  const auto& bodies = dwc->bodies();
  const auto writeAll = [&] {
    if (!file.is_open()) return;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      writePoseRow(file, sim.time(), bodies[b].name, sim.bodyPose(rwsim::dynamics::BodyId(b)));
    }
  };
  writeAll();
  const auto start = std::chrono::steady_clock::now();
  rwsim::simulator::StepStatus status = rwsim::simulator::StepStatus::kOk;
  int steps = 0;
  while (sim.time() < duration - 1e-9 && status == rwsim::simulator::StepStatus::kOk) {
    status = sim.step();
    ++steps;
    if (status == rwsim::simulator::StepStatus::kOk) writeAll();
  }
  const double wall =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "simulated " << fmt(sim.time()) << " s in " << steps << " steps of "
            << fmt(options.timeStep) << " s (" << fmt(wall * 1e3, 4) << " ms wall, "
            << options.stepMethod << ")\n";
  if (status != rwsim::simulator::StepStatus::kOk) {
    std::cerr << "visgrab sim: simulation failed at t = " << fmt(sim.time())
              << " s: " << sim.failureDetail() << "\n";
    return 1;
  }
  if (!file.is_open()) {
    std::cout << "final poses (x y z m, qw qx qy qz):\n";
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      const Transform3D X = sim.bodyPose(rwsim::dynamics::BodyId(b));
      const Eigen::Quaterniond q(X.linear());
      std::cout << "  " << bodies[b].name << "  " << vectorText(X.translation()) << "  "
                << fmt(q.w()) << " " << fmt(q.x()) << " " << fmt(q.y()) << " " << fmt(q.z())
                << "\n";
    }
  }
  return 0;
}

// --- visgrab grasp ------------------------------------------------------------------------

Eigen::VectorXd dofVector(const std::map<std::string, std::vector<double>>& lists,
                          const std::string& name, int dof, const std::string& hand,
                          bool required) {
  const auto it = lists.find(name);
  if (it == lists.end()) {
    if (required)
      throw UsageError("--" + name + " is required (" + std::to_string(dof) + " values for " +
                       hand + ")");
    return {};
  }
  if (static_cast<int>(it->second.size()) != dof) {
    throw UsageError("--" + name + " has " + std::to_string(it->second.size()) + " values but " +
                     hand + " has " + std::to_string(dof) + " DOF");
  }
  return Eigen::Map<const Eigen::VectorXd>(it->second.data(), dof);
}

std::string handName(const std::optional<std::string>& hand, const DynamicWorkCell& dwc) {
  std::string names;
  for (const auto& d : dwc.devices()) names += (names.empty() ? "" : ", ") + d.device->name();
  if (hand) {
    if (!dwc.findDevice(*hand).valid()) {
      throw UsageError("no rigid device '" + *hand +
                       "' (devices: " + (names.empty() ? "none" : names) + ")");
    }
    return *hand;
  }
  if (dwc.devices().size() == 1) return dwc.devices()[0].device->name();
  throw UsageError("--hand is required (devices: " + (names.empty() ? "none" : names) + ")");
}

void printResult(const rwsim::simulator::GraspTrialResult& r, const DynamicWorkCell& dwc) {
  std::cout << "outcome: " << rwsim::trial::outcomeName(r.outcome) << " (RobWork code "
            << rwsim::trial::robworkCode(r.outcome) << ")\n"
            << "Q_lift: " << fmt(r.qLift) << "\nQ_GWS: " << fmt(r.qGws)
            << " (cones on the measured contact forces, the paper's)\nQ_GWS,unit: "
            << fmt(r.qGwsUnit) << " (unit normal forces)\n"
            << "object: " << (r.object.valid() ? dwc.body(r.object).name : "-")
            << "\nsimulated time: " << fmt(r.simulatedTime) << " s\n"
            << "q grasp: " << vectorText(r.qGrasp) << "\n";
  if (r.outcome == rwsim::trial::GraspOutcome::kStable ||
      r.outcome == rwsim::trial::GraspOutcome::kSlipped) {
    std::cout << "hand lift h: " << vectorText(r.handLift)
              << " m, object lift o: " << vectorText(r.objectLift) << " m\n";
  }
  if (!r.detail.empty()) std::cout << "detail: " << r.detail << "\n";
  std::cout << "contacts after lifting (object frame; position m, normal into the object, "
               "normal force N, mu, whole force N, hand link): "
            << r.contacts.size() << "\n";
  for (const auto& c : r.contacts) {
    std::cout << "  p " << vectorText(c.position) << "  n " << vectorText(c.normal, 4) << "  f "
              << fmt(c.normalForce, 4) << "  mu " << fmt(c.mu, 3) << "  F "
              << vectorText(c.force, 4) << "  link "
              << (c.handBody.valid() ? dwc.body(c.handBody).name : "-") << "\n";
  }
}

std::vector<double> numbersOf(const Eigen::VectorXd& v) {
  return std::vector<double>(v.data(), v.data() + v.size());
}

// `visgrab grasp --json` (docs/schemas/grasp.schema.json). Returns the exit code.
int printResultJson(const std::string& hand, const std::string& tcp, const std::string& controller,
                    const rwsim::simulator::GraspTrialResult& r, const DynamicWorkCell& dwc) {
  JsonWriter j(std::cout);
  j.beginObject().key("schema").value("visgrab/grasp/1");
  j.key("hand").value(hand).key("tcp").value(tcp).key("controller").value(controller);
  j.key("outcome").value(std::string(rwsim::trial::outcomeName(r.outcome)));
  j.key("robwork_code").value(rwsim::trial::robworkCode(r.outcome));
  j.key("q_lift").value(r.qLift).key("q_gws").value(r.qGws).key("q_gws_unit").value(r.qGwsUnit);
  j.key("object");
  if (r.object.valid()) {
    j.value(dwc.body(r.object).name);
  } else {
    j.null();
  }
  j.key("simulated_time").value(r.simulatedTime).key("q_grasp").numbers(numbersOf(r.qGrasp));
  j.key("hand_lift").numbers(numbersOf(r.handLift));
  j.key("object_lift").numbers(numbersOf(r.objectLift));
  j.key("detail").value(r.detail).key("contacts").beginArray();
  for (const auto& c : r.contacts) {
    j.beginObject().key("position").numbers(numbersOf(c.position));
    j.key("normal").numbers(numbersOf(c.normal)).key("normal_force").value(c.normalForce);
    j.key("mu").value(c.mu).key("force").numbers(numbersOf(c.force)).key("hand_link");
    if (c.handBody.valid()) {
      j.value(dwc.body(c.handBody).name);
    } else {
      j.null();
    }
    j.endObject();
  }
  j.endArray().endObject().finish();
  return 0;
}

// True if --hand names a hand description (a folder or a *.grasp.xml file), not a device.
bool isHandDescription(const std::string& value) {
  std::error_code ec;
  return std::filesystem::is_directory(value, ec) || value.ends_with(".grasp.xml");
}

/// What `visgrab grasp` was asked for.
struct GraspCommand {
  /// The options with several numbers: pose, qopen, qclose, taumax.
  std::map<std::string, std::vector<double>> lists;
  /// --hand: a device name, or (when `description` is set) a hand description.
  std::optional<std::string> hand;
  /// True when --hand names a hand description (a folder or a *.grasp.xml file).
  bool description = false;
  std::optional<std::string> preshape;
  /// --db and --scene (both or neither).
  std::optional<std::string> db, scene;
  /// The dynamic workcell file (without --db).
  std::string file;
  std::optional<std::string> tcp, controller;
  /// --dt (nullopt: the scene's own time step).
  std::optional<double> dt;
  /// --data (where the default hand is).
  std::filesystem::path data;
  /// --json: print the result as JSON (docs/schemas/grasp.schema.json).
  bool json = false;
};

GraspCommand parseGraspArguments(const Arguments& a) {
  const auto lists = numberLists(a, {"pose", "qopen", "qclose", "taumax"});
  const auto pose = lists.find("pose");
  if (pose == lists.end()) throw UsageError("--pose x y z roll pitch yaw is required");
  if (pose->second.size() != 6) {
    throw UsageError("--pose needs 6 numbers (x y z in m, roll pitch yaw in degrees), got " +
                     std::to_string(pose->second.size()));
  }
  GraspCommand command;
  command.lists = lists;
  command.hand = a.option("hand");
  command.description = command.hand && isHandDescription(*command.hand);
  command.preshape = a.option("preshape");
  command.db = a.option("db");
  command.scene = a.option("scene");
  if (command.db || command.scene) {
    if (!command.db || !command.scene) throw UsageError("--db DIR and --scene ID go together");
    a.requirePositionals(0, "no FILE with --db and --scene");
    if (command.hand && !command.description) {
      throw UsageError("--hand with --db names a hand: its folder or *.grasp.xml");
    }
  } else {
    a.requirePositionals(1, "FILE (a .dwc.xml dynamic workcell), or --db DIR --scene ID");
    command.file = a.positionals()[0];
  }
  command.tcp = a.option("tcp");
  command.controller = a.option("controller");
  if (a.option("dt")) command.dt = positiveOption(a, "dt", std::nullopt);
  command.data = dataFolder(a);
  command.json = a.flag("json");
  return command;
}

/// The scene of a grasp trial and the hand's description, when there is one.
struct GraspScene {
  std::unique_ptr<grasp::HandGraspSetup> description;
  std::unique_ptr<DynamicWorkCell> dwc;
};

/// Loads the scene: a database scene with the hand put in as the benchmark does
/// (session::SceneLoader), or a dynamic workcell file. A null dwc after printing the errors.
GraspScene loadGraspScene(const GraspCommand& command) {
  GraspScene scene;
  if (command.description) scene.description = grasp::loadHandGraspSetup(*command.hand);
  if (command.db) {
    const auto db = database::Database::openAny(*command.db);
    if (!scene.description) {
      scene.description = grasp::loadHandGraspSetup(command.data / "hands/sdh");
    }
    scene.dwc = session::SceneLoader(db, *scene.description).load(db.scene(*command.scene));
  } else {
    scene.dwc = load(command.file);
  }
  return scene;
}

/// The trial setup: the benchmark's for a hand description (session::trialSetup), else the
/// device --hand names with the scene's simulator options; then --tcp, --controller and --dt.
rwsim::simulator::GraspTrialSetup graspTrialSetup(const GraspCommand& command,
                                                  const GraspScene& scene) {
  const DynamicWorkCell& dwc = *scene.dwc;
  rwsim::simulator::GraspTrialSetup setup;
  if (scene.description) {
    setup = session::trialSetup(*scene.description, dwc);
    if (!dwc.findDevice(setup.hand).valid()) {
      throw UsageError("the dynamic workcell has no device '" + setup.hand + "' (the hand of " +
                       scene.description->description().file + ")");
    }
  } else {
    setup.hand = handName(command.hand, dwc);
    setup.simulator = rwsim::simulator::optionsFromEngineProperties(dwc);
  }
  if (command.tcp) {
    if (scene.description) {
      throw UsageError("--tcp goes with --hand NAME only: a hand description sets its own TCP (" +
                       scene.description->tcpFrameName() + ")");
    }
    setup.tcpFrame = *command.tcp;
  }
  setup.controller = command.controller.value_or(setup.controller);
  setup.simulator.timeStep = command.dt.value_or(setup.simulator.timeStep);
  return setup;
}

/// The TCP pose of --pose (position in m, RobWork RPY in degrees).
rw::math::Transform3D tcpPose(const GraspCommand& command) {
  const auto& v = command.lists.at("pose");
  return rw::math::rpyTransform(rw::math::Vector3D(v[3], v[4], v[5]) * rw::math::kDeg2Rad,
                                rw::math::Vector3D(v[0], v[1], v[2]));
}

/// --qopen, --qclose and --taumax over `grasp`'s values (all three lists are required when
/// `required`; an absent one keeps its value).
void applyJointLists(const GraspCommand& command, int dof, const std::string& hand, bool required,
                     rw::math::Q& qOpen, rw::math::Q& qClosed, rw::math::Q& tauMax) {
  const auto& lists = command.lists;
  if (required || lists.count("qopen") > 0) qOpen = dofVector(lists, "qopen", dof, hand, required);
  if (required || lists.count("qclose") > 0) {
    qClosed = dofVector(lists, "qclose", dof, hand, required);
  }
  if (required || lists.count("taumax") > 0) tauMax = dofVector(lists, "taumax", dof, hand, false);
  if (tauMax.size() > 0 && tauMax.minCoeff() < 0.0) {
    throw UsageError("--taumax values must be >= 0");
  }
}

/// The grasp as the benchmark reads one from a grasp file, for a hand with a grasp description:
/// a pre-shape grasp for --preshape alone; else a raw grasp (the pre-shape's values, at its TCP,
/// under --qopen, --qclose and --taumax), whose tau_max, when none is given, comes from the
/// hand's torque rule as in a grasp file.
grasp::GraspRequest graspRequest(const GraspCommand& command,
                                 const grasp::HandGraspSetup& description, int dof,
                                 const std::string& hand) {
  grasp::GraspRequest request;
  request.sceneId = command.scene.value_or("");
  request.id = "of the command line";
  request.method = "grasp";
  request.X_W_tcp = tcpPose(command);
  request.kind = grasp::GraspKind::kRaw;
  const auto& lists = command.lists;
  const bool overridden =
      lists.count("qopen") > 0 || lists.count("qclose") > 0 || lists.count("taumax") > 0;
  if (command.preshape) {
    const grasp::PreShape* shape = description.findPreshape(*command.preshape);
    if (shape == nullptr) {
      std::string names;
      for (const auto& p : description.preshapes()) names += (names.empty() ? "" : ", ") + p.name;
      throw UsageError("--preshape: the hand has no pre-shape '" + *command.preshape + "' (" +
                       names + ")");
    }
    if (!overridden) {
      request.kind = grasp::GraspKind::kPreshape;
      request.preshape = *command.preshape;
      return request;
    }
    // The pose is the pre-shape's TCP frame (as in grasp files).
    request.X_W_tcp = request.X_W_tcp * shape->X_shapeTcp_tcp;
    request.qOpen = shape->qOpen;
    request.qClosed = shape->qClosed;
    request.tauMax = shape->tauMax;
  }
  applyJointLists(command, dof, hand, !command.preshape, request.qOpen, request.qClosed,
                  request.tauMax);
  return request;
}

/// A raw grasp for a device without a grasp description: --pose, --qopen, --qclose, --taumax
/// (no tau_max: the controller's limits).
rwsim::simulator::GraspParameters rawGrasp(const GraspCommand& command, int dof,
                                           const std::string& hand) {
  rwsim::simulator::GraspParameters grasp;
  grasp.X_W_tcp = tcpPose(command);
  applyJointLists(command, dof, hand, true, grasp.qOpen, grasp.qClosed, grasp.tauMax);
  return grasp;
}

int runGrasp(const Arguments& a) {
  const GraspCommand command = parseGraspArguments(a);
  const GraspScene scene = loadGraspScene(command);
  if (!scene.dwc) return 1;
  if (command.preshape && !scene.description) {
    throw UsageError("--preshape needs --hand DIR|GRASP.xml (a hand description with pre-shapes)");
  }
  rwsim::simulator::GraspTrialSetup setup = graspTrialSetup(command, scene);
  if (const auto protocol = protocolOption(a)) {
    setup.protocol = rwsim::trial::loadTrialProtocol(*protocol);
    try {
      setup.protocol.requireJawFrame(setup.X_tcp_jaw.has_value(),
                                     scene.description
                                         ? "the hand of " + scene.description->description().file
                                         : "device " + setup.hand);
    } catch (const std::invalid_argument& e) {
      throw UsageError(std::string("--protocol: ") + e.what());
    }
  }
  const std::string engineName = engineOption(a);
  std::unique_ptr<rwsim::simulator::GraspTrial> trial;
  try {
    auto engine = rwsim::engines::engineFactory(engineName, *scene.dwc, setup);
    trial = std::make_unique<rwsim::simulator::GraspTrial>(*scene.dwc, setup, std::move(engine));
  } catch (const std::invalid_argument& e) {
    throw UsageError(e.what());
  }
  const DynamicWorkCell& dwc = *scene.dwc;
  const int dof = dwc.device(trial->handDevice()).device->dof();
  const rw::kinematics::State initial = dwc.workcell().defaultState();
  rwsim::simulator::GraspParameters grasp;
  if (scene.description) {
    // Through the benchmark's door: grasp::resolve, with placements tested in this scene as
    // session::SceneSession::resolve does.
    const grasp::ResolvedGrasp resolved =
        grasp::resolve(graspRequest(command, *scene.description, dof, setup.hand),
                       *scene.description, [&](const rwsim::simulator::GraspParameters& g) {
                         return trial->checkPlacement(g, initial);
                       });
    if (!resolved.ok()) throw UsageError(resolved.message);
    grasp = resolved.parameters;
  } else {
    grasp = rawGrasp(command, dof, setup.hand);
  }
  if (command.json) {
    return printResultJson(setup.hand, dwc.workcell().frames().frame(trial->tcpFrame()).name(),
                           setup.controller, trial->run(grasp, initial), dwc);
  }
  std::cout << "hand " << setup.hand << ", TCP "
            << dwc.workcell().frames().frame(trial->tcpFrame()).name() << ", controller "
            << setup.controller << ", engine " << trial->engine().name() << "\n";
  printResult(trial->run(grasp, initial), dwc);
  return 0;
}

}  // namespace

void addSimulationCommands(CommandLine& cli) {
  CLI::App& sim = cli.addCommand(
      nullptr, "sim",
      "Simulate a dynamic workcell for T seconds; write every body's pose per step as CSV "
      "(time,body,x,y,z,qw,qx,qy,qz; m) or print the final poses.",
      guarded(runSim));
  sim.add_option("FILE", "The dynamic workcell (.dwc.xml)")->required()->type_name("");
  sim.add_option("--time", "Simulated time in s")
      ->required()
      ->type_name("SECONDS")
      ->check(positiveNumber());
  sim.add_option("--dt", "Time step in s (default: the workcell's engine properties)")
      ->type_name("SECONDS")
      ->check(positiveNumber());
  sim.add_option("--out", "Write the poses of every step to this CSV file")->type_name("poses.csv");

  CLI::App& grasp = cli.addCommand(
      nullptr, "grasp",
      "Run one grasp trial; print the outcome, RobWork code, Q_lift, Q_GWS and contacts. "
      "--hand names a device of FILE, or a hand (its folder or grasp description: device, "
      "controller, TCP and --preshape from it); --db/--scene run it in a database scene with "
      "that hand put in (default the SDH). Give FILE before the number lists (or end a list "
      "with --).",
      guarded(runGrasp));
  grasp.add_option("FILE", "The dynamic workcell (.dwc.xml); or --db and --scene")->type_name("");
  grasp.add_option("--db", kDatabaseOptionHelp)->type_name("DIR|MANIFEST");
  grasp.add_option("--scene", "The database scene (with --db)")->type_name("ID");
  grasp
      .add_option("--hand",
                  "A device of FILE, or a hand: its folder or grasp description (default: the "
                  "only device of FILE; with --db the SDH)")
      ->type_name("NAME|DIR|GRASP.xml");
  addNumberList(grasp, "--pose", "X Y Z ROLL PITCH YAW",
                "The TCP pose: position in m, RobWork RPY in degrees (Rz Ry Rx, as in .wc.xml)")
      ->required();
  addNumberList(grasp, "--qopen", "Q", "Open joint values, one per DOF (rad or m)");
  addNumberList(grasp, "--qclose", "Q", "Closed joint values, one per DOF (rad or m)");
  addNumberList(grasp, "--taumax", "T",
                "Joint force limits, one per DOF (N m or N; default: the pre-shape's, else the "
                "hand description's torque rule at --qopen as for a raw grasp in a grasp file, "
                "else the controller's)");
  grasp
      .add_option("--preshape",
                  "A pre-shape of the hand description: its qopen, qclose, taumax and TCP offset")
      ->type_name("NAME");
  grasp.add_option("--tcp", "The TCP frame (with --hand NAME only)")->type_name("FRAME");
  grasp.add_option("--controller", "The hand's controller (default: the hand's own)")
      ->type_name("NAME");
  grasp.add_option("--dt", "ODE's time step in s (default: the workcell's engine properties)")
      ->type_name("SECONDS")
      ->check(positiveNumber());
  addEngineOption(grasp);
  addProtocolOption(grasp);
  addDataOption(grasp);
  addFlag(grasp, "--json", "Print JSON instead (docs/schemas/grasp.schema.json; SI units)");
}

}  // namespace visgrab::app
