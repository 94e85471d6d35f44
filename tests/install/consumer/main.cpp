// Links an installed VisGraB: writes a scene (a 6 x 6 x 10 cm box on a table) next to the
// installed SDH hand, loads it and runs one grasp trial with the hand's cylinder pre-shape
// around the box. Prints "outcome <name> contacts <n> object <body>"; exit 0 when it ran.
//
// usage: consumer SCENES_DIR OUT_DIR  (SCENES_DIR: the installed share/visgrab/scenes)
#include <exception>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <iostream>
#include <numbers>
#include <stdexcept>
#include <string>

#include "rw/math/rpy.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/simulator/grasp_trial.hpp"

namespace fs = std::filesystem;

namespace {

void write(const fs::path& file, const std::string& text) {
  std::ofstream out(file);
  out << text;
  if (!out) throw std::runtime_error("cannot write " + file.string());
}

rw::math::Q q(std::initializer_list<double> values) {
  rw::math::Q out(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (const double v : values) out[i++] = v;
  return out;
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

    // The hand pointing down, its TCP at the box's centre, fingers around it.
    rwsim::simulator::GraspParameters grasp;
    grasp.X_W_tcp = rw::math::rpyTransform(rw::math::Vector3D(0, std::numbers::pi, 0),
                                           rw::math::Vector3D(0, 0, 0.05));
    grasp.qOpen = q({-1.048, 0.174, 0.0, -1.048, 0.174, -1.048, 0.174});
    grasp.qClosed = q({0.0, 0.349, 0.0, 0.0, 0.349, 0.0, 0.349});
    grasp.tauMax = q({2.1, 1.4, 2.1, 1.05, 0.7, 1.05, 0.7});
    const auto result = trial.run(grasp, dwc->workcell().defaultState());

    const std::string object =
        result.object.valid() ? dwc->body(result.object).name : std::string("none");
    std::cout << "outcome " << rwsim::simulator::outcomeName(result.outcome) << " contacts "
              << result.contacts.size() << " object " << object << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "consumer: " << e.what() << "\n";
    return 1;
  }
}
