#include "rwsim/dynamics/loop_closure.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace rwsim::dynamics {

namespace {

using rw::kinematics::FrameId;

// The body a leg end rides on, and the joints without a link body on the way up to it.
struct Carrier {
  BodyId body;
  std::vector<FrameId> bodylessJoints;
};

Carrier carrierOf(const DynamicWorkCell& dwc, FrameId end) {
  const auto& tree = dwc.workcell().frames();
  Carrier c;
  for (FrameId f = end; f.valid(); f = tree.frame(f).parent()) {
    c.body = dwc.bodyOfFrame(f);
    if (c.body.valid()) return c;
    if (tree.frame(f).isJoint()) c.bodylessJoints.push_back(f);
    if (f == rw::kinematics::FrameTree::kWorld) break;
  }
  c.body = BodyId::none();
  return c;
}

bool ofDevice(const RigidDevice& device, BodyId body) {
  return body.valid() &&
         (body == device.baseBody || std::find(device.linkBodies.begin(), device.linkBodies.end(),
                                               body) != device.linkBodies.end());
}

}  // namespace

std::vector<LoopClosure> loopClosures(const DynamicWorkCell& dwc, const RigidDevice& device) {
  std::vector<LoopClosure> closures;
  const auto* parallel = device.device == nullptr ? nullptr : device.device->parallel();
  if (parallel == nullptr) return closures;
  const auto& tree = dwc.workcell().frames();
  const auto& junctions = parallel->junctions();
  for (std::size_t j = 0; j < junctions.size(); ++j) {
    const auto& legs = junctions[j].legs;
    const Carrier first = carrierOf(dwc, legs[0].end);
    for (std::size_t i = 1; i < legs.size(); ++i) {
      const std::string what = "device \"" + device.device->name() + "\", junction " +
                               std::to_string(j) + ", leg " + std::to_string(i) + ": ";
      const Carrier other = carrierOf(dwc, legs[i].end);
      if (!ofDevice(device, first.body) || !ofDevice(device, other.body)) {
        throw std::invalid_argument(what + "a leg end hangs on no body of the device");
      }
      const std::size_t bodyless = first.bodylessJoints.size() + other.bodylessJoints.size();
      if (bodyless > 1) {
        std::string names;
        for (const auto* list : {&first.bodylessJoints, &other.bodylessJoints}) {
          for (const FrameId f : *list) names += (names.empty() ? "" : ", ") + tree.frame(f).name();
        }
        throw std::invalid_argument(what + "the joints " + names +
                                    " have no link body; one of them can close the loop, give "
                                    "the others a <Link>");
      }
      if (first.body == other.body) {
        throw std::invalid_argument(what + "both leg ends ride on body \"" +
                                    dwc.body(first.body).name + "\"; nothing closes the loop");
      }
      LoopClosure c;
      c.junction = j;
      c.leg = i;
      c.parent = first.body;
      c.child = other.body;
      if (!first.bodylessJoints.empty()) {
        c.joint = first.bodylessJoints.front();
      } else if (!other.bodylessJoints.empty()) {
        c.joint = other.bodylessJoints.front();
        std::swap(c.parent, c.child);
      }
      if (c.joint.valid() && tree.frame(c.joint).isDependent()) {
        throw std::invalid_argument(what + "the closing joint " + tree.frame(c.joint).name() +
                                    " is dependent; give it a <Link>");
      }
      closures.push_back(c);
    }
  }
  return closures;
}

}  // namespace rwsim::dynamics
