#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "support/test_support.hpp"

/// A small scene for the dynamic workcell loader tests, written to a temporary folder.
namespace visgrab::test::dwc {

/// The workcell: a table, a movable object with a fixed "Handle" below it, a movable frame
/// without geometry ("Ghost"), a floor plane, and the project's SDH (scenes/hands/sdh) mounted
/// on "Mount".
inline std::string sceneWorkCell() {
  const std::string sdh = (sourceDir() / "scenes/hands/sdh/sdh.wc.xml").string();
  return R"(<WorkCell name="Scene">
  <Frame name="Table" refframe="WORLD">
    <RPY>0 0 0</RPY><Pos>0 0 0</Pos>
    <Drawable name="Top"><RPY>0 0 0</RPY><Pos>0 0 -0.05</Pos><Box x="1" y="1" z="0.1"/></Drawable>
  </Frame>
  <Frame name="Object" refframe="WORLD" type="Movable">
    <RPY>0 0 0</RPY><Pos>0 0 0.2</Pos>
    <Drawable name="Body"><RPY>0 0 0</RPY><Pos>0.01 0 0</Pos><Box x="0.1" y="0.2" z="0.3"/></Drawable>
  </Frame>
  <Frame name="Handle" refframe="Object">
    <RPY>0 0 0</RPY><Pos>0 0 0.2</Pos>
    <Drawable name="Knob"><RPY>0 0 0</RPY><Pos>0 0 0</Pos><Box x="0.1" y="0.1" z="0.1"/></Drawable>
  </Frame>
  <Frame name="Ghost" refframe="WORLD" type="Movable">
    <RPY>0 0 0</RPY><Pos>1 0 0</Pos>
  </Frame>
  <Frame name="Floor" refframe="WORLD">
    <RPY>0 0 0</RPY><Pos>0 0 -0.1</Pos>
    <Drawable name="Ground"><RPY>0 0 0</RPY><Pos>0 0 0</Pos><Plane/></Drawable>
  </Frame>
  <Frame name="Mount" refframe="WORLD">
    <RPY>0 0 0</RPY><Pos>0 0 0.5</Pos>
  </Frame>
  <Include file=")" +
         sdh + R"("/>
</WorkCell>
)";
}

/// Materials Plastic (default) and Rubber, object types hard (default) and soft.
inline const char* kMaterials = R"(<IncludeData>
  <MaterialData>
    <Default>Plastic</Default>
    <Material id="Plastic"/>
    <Material id="Rubber"/>
  </MaterialData>
  <FrictionMap>
    <Pair first="Plastic" second="Rubber"><FrictionData type="Coulomb"><Mu>0.7</Mu></FrictionData></Pair>
  </FrictionMap>
  <ObjectTypeData>
    <Default>hard</Default>
    <ObjectType id="hard"/>
    <ObjectType id="soft"/>
  </ObjectTypeData>
</IncludeData>
)";

/// The SDH's joints in device order.
inline const std::vector<std::string> kSdhJoints = {"f1.Joint2", "f1.Joint3", "F2Joint1",
                                                    "f2.Joint2", "f2.Joint3", "F3Joint1",
                                                    "f3.Joint2", "f3.Joint3"};

/// A RigidDevice for the SDH: one ForceLimit per joint except `skipLimit`, a kinematic base
/// and a RigidJoint per joint; `extra` is inserted before </RigidDevice>. One element a line.
inline std::string sdhDevice(const std::string& skipLimit = "", const std::string& extra = "") {
  std::string text = "<RigidDevice device=\"SchunkHand\">\n";
  for (const std::string& j : kSdhJoints) {
    if (j != skipLimit) text += "<ForceLimit joint=\"" + j + "\">2</ForceLimit>\n";
  }
  text += "<KinematicBase frame=\"Base\"><MaterialID>Plastic</MaterialID></KinematicBase>\n";
  for (const std::string& j : kSdhJoints) {
    text += "<RigidJoint joint=\"" + j + "\"><Mass>0.1</Mass><EstimateInertia/></RigidJoint>\n";
  }
  return text + extra + "</RigidDevice>\n";
}

/// A PD controller for the SDH with `pairs` pairs of gains and the given Sync text.
inline std::string sdhController(int pairs = 7, const std::string& sync = "false") {
  std::string gains;
  for (int i = 0; i < pairs; ++i) gains += " 10 0.003";
  return "<PDDeviceController name=\"GraspController\" device=\"SchunkHand\" type=\"Position\">"
         "<Sync>" +
         sync + "</Sync><PDParams>" + gains + "</PDParams></PDDeviceController>\n";
}

/// A temporary folder holding scene.wc.xml and materials.xml.
class SceneDir {
 public:
  SceneDir() {
    writeFile(dir_.path() / "scene.wc.xml", sceneWorkCell());
    writeFile(dir_.path() / "materials.xml", kMaterials);
  }
  /// The folder.
  const std::filesystem::path& path() const { return dir_.path(); }
  /// `<DynamicWorkcell workcell="scene.wc.xml">` + `<Include file="materials.xml"/>` on lines 1
  /// and 2, then `body` from line 3, then `</DynamicWorkcell>`.
  static std::string dwc(const std::string& body) {
    return "<DynamicWorkcell workcell=\"scene.wc.xml\">\n<Include file=\"materials.xml\"/>\n" +
           body + "</DynamicWorkcell>\n";
  }
  /// Writes `text` as top.dwc.xml and returns its path.
  std::filesystem::path writeTop(const std::string& text) const {
    return writeFile(dir_.path() / "top.dwc.xml", text);
  }

 private:
  TempDir dir_;
};

}  // namespace visgrab::test::dwc
