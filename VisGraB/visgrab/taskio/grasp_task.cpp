#include "visgrab/taskio/grasp_task.hpp"

#include <stdexcept>

namespace visgrab::taskio {

using rw::math::Transform3D;

std::optional<std::string> stringProperty(const std::vector<Property>& properties,
                                          std::string_view name) {
  for (const auto& p : properties) {
    if (p.name == name && p.value.name == "String") {
      return std::string(rw::common::trimXmlSpace(p.value.text));
    }
  }
  return std::nullopt;
}

void setStringProperty(std::vector<Property>& properties, std::string_view name,
                       std::string_view value) {
  rw::common::XmlElement element;
  element.name = "String";
  element.text = std::string(value);
  for (auto& p : properties) {
    if (p.name == name) {
      p.value = std::move(element);
      return;
    }
  }
  properties.push_back(Property{std::string(name), "", std::move(element)});
}

std::size_t GraspTask::targetCount() const {
  std::size_t n = 0;
  for (const auto& sub : subTasks) n += sub.targets.size();
  return n;
}

std::vector<grasp::GraspRequest> toGraspRequests(const GraspTask& task, std::string_view sceneId,
                                                 std::string_view method,
                                                 const FrameResolver& resolve) {
  std::vector<grasp::GraspRequest> out;
  out.reserve(task.targetCount());
  for (std::size_t s = 0; s < task.subTasks.size(); ++s) {
    const GraspSubTask& sub = task.subTasks[s];
    Transform3D X_W_ref = Transform3D::Identity();
    if (!sub.targets.empty() && !sub.refframe.empty() && sub.refframe != "WORLD") {
      std::optional<Transform3D> found;
      if (resolve) found = resolve(sub.refframe);
      if (!found) {
        throw std::invalid_argument("sub-task " + std::to_string(s) + ": refframe '" +
                                    sub.refframe + "' is not WORLD and cannot be resolved");
      }
      X_W_ref = *found;
    }
    const auto visgrabId = stringProperty(sub.otherProperties, "VisGraBID");
    const std::string prefix = sub.taskId.empty() ? std::to_string(s) : sub.taskId;
    for (std::size_t t = 0; t < sub.targets.size(); ++t) {
      grasp::GraspRequest r;
      r.sceneId = std::string(sceneId);
      r.method = std::string(method);
      r.id = (visgrabId && sub.targets.size() == 1) ? *visgrabId : prefix + "." + std::to_string(t);
      r.kind = grasp::GraspKind::kRaw;
      r.X_W_tcp = X_W_ref * sub.offset * sub.targets[t].pose;
      r.qOpen = sub.openQ;
      r.qClosed = sub.closeQ;
      r.tauMax = sub.tauMax;
      r.sourceLine = sub.targets[t].sourceLine;
      out.push_back(std::move(r));
    }
  }
  return out;
}

GraspTask fromGraspRequests(const std::vector<grasp::GraspRequest>& requests,
                            std::string_view gripperId, std::string_view tcpId,
                            std::string_view graspControllerId) {
  GraspTask task;
  task.gripperId = std::string(gripperId);
  task.tcpId = std::string(tcpId);
  task.graspControllerId = std::string(graspControllerId);
  if (!requests.empty()) setStringProperty(task.otherProperties, "SceneID", requests[0].sceneId);
  for (const auto& r : requests) {
    if (r.kind != grasp::GraspKind::kRaw) {
      throw std::invalid_argument("grasp '" + r.id + "' is of kind " + grasp::kindName(r.kind) +
                                  "; only raw grasps can be written as a RobWork task");
    }
    GraspSubTask sub;
    sub.retract = rw::math::makeTranslation(rw::math::Vector3D(0, 0, 0.1));
    sub.openQ = r.qOpen;
    sub.closeQ = r.qClosed;
    sub.tauMax = r.tauMax;
    setStringProperty(sub.otherProperties, "VisGraBID", r.id);
    GraspTarget target;
    target.pose = r.X_W_tcp;
    sub.targets.push_back(std::move(target));
    task.subTasks.push_back(std::move(sub));
  }
  return task;
}

GraspTarget& targetAt(GraspTask& task, std::size_t index) {
  std::size_t remaining = index;
  for (auto& sub : task.subTasks) {
    if (remaining < sub.targets.size()) return sub.targets[remaining];
    remaining -= sub.targets.size();
  }
  throw std::out_of_range("grasp task has no target " + std::to_string(index) + " (it has " +
                          std::to_string(task.targetCount()) + ")");
}

void setResult(GraspTarget& target, rwsim::trial::GraspOutcome outcome, double qLift, double qGws,
               double qGwsUnit, const rw::math::Q& qGrasp) {
  if (!target.result) target.result.emplace();
  GraspResult& r = *target.result;
  r.testStatus = rwsim::trial::robworkCode(outcome);
  r.liftResult = qLift;
  r.qualityAfterLifting = rw::math::Q::Constant(1, qLift);
  r.qualityBeforeLifting = rw::math::Q(2);
  r.qualityBeforeLifting << qGws, qGwsUnit;
  r.gripperConfigurationGrasp = qGrasp;
}

}  // namespace visgrab::taskio
