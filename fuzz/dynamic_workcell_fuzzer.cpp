// Dynamic workcell files (.dwc.xml) through rwsim::loaders::loadDynamicWorkCell, the program's
// entry point. The scratch folder also holds a small workcell (scene.wc.xml: a table, a box and
// a one-joint gripper) and a material file (materials.xml) for the input to name, so that the
// bodies, devices and controllers it declares get built; LoadError is the documented outcome.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_support.hpp"
#include "rw/common/diagnostic.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"

namespace {

constexpr const char* kSceneWorkCell = R"(<WorkCell name="FuzzScene">
  <Frame name="Table" refframe="WORLD">
    <RPY>0 0 0</RPY><Pos>0 0 -0.05</Pos>
    <Drawable name="Slab"><RPY>0 0 0</RPY><Pos>0 0 0</Pos><Box x="1" y="1" z="0.1"/></Drawable>
  </Frame>
  <Frame name="Box" refframe="WORLD" type="Movable">
    <RPY>0 0 0</RPY><Pos>0 0 0.05</Pos>
    <Drawable name="Cube"><RPY>0 0 0</RPY><Pos>0 0 0</Pos><Box x="0.1" y="0.1" z="0.1"/></Drawable>
  </Frame>
  <Frame name="Mount" refframe="WORLD"><RPY>0 180 0</RPY><Pos>0 0 0.4</Pos></Frame>
  <TreeDevice name="Gripper">
    <Frame name="Base" refframe="Mount" type="Movable">
      <RPY>0 0 0</RPY><Pos>0 0 0</Pos>
      <Drawable name="Palm"><RPY>0 0 0</RPY><Pos>0 0 0.02</Pos><Box x="0.05" y="0.1" z="0.04"/></Drawable>
    </Frame>
    <Joint name="Jaw" refframe="Base" type="Prismatic">
      <RPY>0 0 90</RPY><Pos>0 -0.02 0.05</Pos>
      <PosLimit min="0" max="0.04"/><VelLimit max="0.1"/>
      <Drawable name="JawA"><RPY>0 0 0</RPY><Pos>0 0.02 0</Pos><Box x="0.02" y="0.04" z="0.01"/></Drawable>
    </Joint>
    <Joint name="Mirror" refframe="Base" type="Prismatic">
      <RPY>0 0 90</RPY><Pos>0 0.02 0.05</Pos>
      <Depend on="Jaw" gain="-1" offset="0"/>
      <Drawable name="JawB"><RPY>0 0 0</RPY><Pos>0 0.02 0</Pos><Box x="0.02" y="0.04" z="0.01"/></Drawable>
    </Joint>
    <Frame name="Tip" refframe="Jaw" type="EndEffector"><RPY>0 0 0</RPY><Pos>0 0 0</Pos></Frame>
    <Q name="Home">0</Q>
  </TreeDevice>
</WorkCell>
)";

constexpr const char* kMaterials = R"(<IncludeData>
  <MaterialData>
    <Default>Object</Default>
    <Material id="Object"/>
    <Material id="Finger"/>
    <Material id="Table"/>
  </MaterialData>
  <FrictionMap>
    <Pair first="Finger" second="Object"><FrictionData type="Coulomb"><Mu>0.6</Mu></FrictionData></Pair>
    <Pair first="Object" second="Table"><FrictionData type="Coulomb"><Mu>0.4</Mu></FrictionData></Pair>
  </FrictionMap>
  <ObjectTypeData>
    <Default>hard</Default>
    <ObjectType id="hard"/>
  </ObjectTypeData>
</IncludeData>
)";

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  visgrab::fuzz::writeScratchFile("scene.wc.xml", kSceneWorkCell);
  visgrab::fuzz::writeScratchFile("materials.xml", kMaterials);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto file =
      visgrab::fuzz::writeScratchFile("fuzz.dwc.xml", visgrab::fuzz::asText(data, size));
  std::vector<rw::common::Diagnostic> warnings;
  try {
    const auto dwc = rwsim::loaders::loadDynamicWorkCell(file, &warnings);
  } catch (const rw::common::LoadError&) {
  }
  return 0;
}
