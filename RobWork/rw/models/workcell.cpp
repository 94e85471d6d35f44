#include "rw/models/workcell.hpp"

#include <stdexcept>
#include <utility>

namespace rw::models {

using rw::kinematics::FrameId;

WorkCell::WorkCell(std::string name) : name_(std::move(name)) {}

rw::kinematics::State WorkCell::defaultState() const {
  if (defaultState_ &&
      defaultState_->values().size() == static_cast<std::size_t>(frames_.stateSize()) &&
      defaultState_->parentCount() == frames_.size()) {
    return *defaultState_;
  }
  return frames_.makeState();
}

void WorkCell::setDefaultState(rw::kinematics::State state) {
  if (state.values().size() != static_cast<std::size_t>(frames_.stateSize()) ||
      state.parentCount() != frames_.size()) {
    throw std::invalid_argument("workcell \"" + name_ +
                                "\": the default state does not fit its frames");
  }
  defaultState_ = std::move(state);
}

void WorkCell::checkNewDeviceName(const std::string& name) const {
  if (findDevice(name) != nullptr) {
    throw std::invalid_argument("device \"" + name + "\" already exists");
  }
}

const Device& WorkCell::addDevice(Device::Spec spec) {
  checkNewDeviceName(spec.name);
  devices_.push_back(std::make_unique<Device>(std::move(spec), frames_));
  return *devices_.back();
}

const Device& WorkCell::addDevice(Device::Spec spec, ParallelStructure structure) {
  checkNewDeviceName(spec.name);
  devices_.push_back(std::make_unique<Device>(std::move(spec), frames_, std::move(structure)));
  return *devices_.back();
}

const Device* WorkCell::findDevice(std::string_view name) const {
  for (const auto& d : devices_) {
    if (d->name() == name) return d.get();
  }
  return nullptr;
}

Object& WorkCell::objectOf(FrameId frame) {
  for (Object& o : objects_) {
    if (o.frame == frame) return o;
  }
  objects_.push_back(Object{frame, {}, {}});
  return objects_.back();
}

const Object* WorkCell::findObject(FrameId frame) const {
  for (const Object& o : objects_) {
    if (o.frame == frame) return &o;
  }
  return nullptr;
}

}  // namespace rw::models
