// Links an installed VisGraB: writes a scene (a 6 x 6 x 10 cm box on a table) with the
// installed SDH hand, loads it (rwsim) and runs one grasp trial with the cylinder pre-shape of the
// installed SDH description (visgrab) around the box. Prints "outcome <name> contacts <n> object
// <body>"; exit 0 when it ran.
//
// usage: consumer SCENES_DIR OUT_DIR  (SCENES_DIR: the installed share/visgrab/scenes)
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <numbers>
#include <stdexcept>
#include <string>

#include "rw/math/rpy.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/simulator/grasp_trial.hpp"
#include "visgrab/grasp/hand_grasp_setup.hpp"

namespace fs = std::filesystem;

namespace {

void write(const fs::path& file, const std::string& text) {
  std::ofstream out(file);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: consumer SCENES_DIR OUT_DIR\n";
    return 2;
  }
  try {
    const fs::path scenes = fs::absolute(argv[1]);
    const fs::path out = argv[2];
    write(out / "box.wc.xml", R"(<WorkCell name="BoxScene">
  <Frame name="Table" refframe="WORLD">
    <RPY>0 0 0</RPY><Pos>0 0 -0.025</Pos>
    <Drawable name="TableGeo"><RPY>0 0 0</RPY><Pos>0 0 0</Pos><Box x="0.8" y="0.8" z="0.05"/></Drawable>
  </Frame>
  <Frame name="Box" refframe="WORLD" type="Movable">
    <RPY>0 0 0</RPY><Pos>0 0 0.05</Pos>
    <Drawable name="BoxGeo"><RPY>0 0 0</RPY><Pos>0 0 0</Pos><Box x="0.06" y="0.06" z="0.1"/></Drawable>
  </Frame>
  <Frame name="HandMount" refframe="WORLD"><RPY>0 180 0</RPY><Pos>0 0 0.4</Pos></Frame>
  <Include file=")" + (scenes / "hands/sdh/sdh.wc.xml").string() +
                                  R"("/>
</WorkCell>
)");
    write(out / "box.dwc.xml", R"(<DynamicWorkcell workcell="box.wc.xml">
  <Gravity>0 0 -9.81</Gravity>
  <Include file=")" + (scenes / "materials.xml").string() +
                                   R"("/>
  <FixedBody frame="Table"><MaterialID>Table</MaterialID></FixedBody>
  <RigidBody frame="Box">
    <Mass>0.2</Mass><EstimateInertia/><Integrator>Euler</Integrator><MaterialID>Object</MaterialID>
  </RigidBody>
  <Include file=")" + (scenes / "hands/sdh/sdh_dynamics.dwc.xml").string() +
                                   R"("/>
</DynamicWorkcell>
)");
    const auto dwc = rwsim::loaders::loadDynamicWorkCell(out / "box.dwc.xml");

    rwsim::simulator::GraspTrialSetup setup;
    setup.hand = "SchunkHand";
    setup.tcpFrame = "SchunkHand.SDHTCP";
    setup.simulator = rwsim::simulator::optionsFromEngineProperties(*dwc);
    const rwsim::simulator::GraspTrial trial(*dwc, setup);

    // The installed SDH description (visgrab layer): its cylinder pre-shape and torque limits.
    const auto hand = visgrab::grasp::loadHandGraspSetup(scenes / "hands/sdh");
    const visgrab::grasp::PreShape* cylinder = hand->findPreshape("SDH_CYL");
    if (cylinder == nullptr) throw std::runtime_error("the installed SDH has no SDH_CYL");

    // The hand pointing down, its TCP at the box's centre, fingers around it.
    rwsim::simulator::GraspParameters grasp;
    grasp.X_W_tcp = rw::math::rpyTransform(rw::math::Vector3D(0, std::numbers::pi, 0),
                                           rw::math::Vector3D(0, 0, 0.05));
    grasp.qOpen = cylinder->qOpen;
    grasp.qClosed = cylinder->qClosed;
    grasp.tauMax =
        cylinder->tauMax.size() > 0 ? cylinder->tauMax : hand->tauRule().evaluate(cylinder->qOpen);
    const auto result = trial.run(grasp, dwc->workcell().defaultState());

    const std::string object =
        result.object.valid() ? dwc->body(result.object).name : std::string("none");
    std::cout << "outcome " << rwsim::trial::outcomeName(result.outcome) << " contacts "
              << result.contacts.size() << " object " << object << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "consumer: " << e.what() << "\n";
    return 1;
  }
}
