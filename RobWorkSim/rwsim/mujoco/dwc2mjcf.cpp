// dwc2mjcf IN.dwc.xml OUT.xml: writes a dynamic workcell as MJCF with the MuJoCo engine's default
// options (rwsim/mujoco/mjcf_export.hpp says what is exported and how), e.g. to inspect it in
// MuJoCo's viewer.
#include <exception>
#include <fstream>
#include <iostream>

#include "rw/common/diagnostic.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "rwsim/mujoco/mjcf_export.hpp"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::cerr << "usage: dwc2mjcf IN.dwc.xml OUT.xml\n";
    return 2;
  }
  try {
    const auto dwc = rwsim::loaders::loadDynamicWorkCell(argv[1]);
    const auto model = rwsim::mujoco::exportMjcf(*dwc);
    for (const auto& frame : model.skippedFrames) {
      std::cerr << argv[1] << ": warning: frame '" << frame
                << "' has collision geometry but belongs to no body; not exported\n";
    }
    std::ofstream out(argv[2], std::ios::binary);
    out << model.xml;
    out.close();
    if (!out) {
      std::cerr << argv[2] << ": error: cannot write the file\n";
      return 1;
    }
  } catch (const rw::common::LoadError& e) {
    std::cerr << e.what() << "\n";  // names the file and line itself
    return 1;
  } catch (const std::exception& e) {
    std::cerr << argv[1] << ": error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
