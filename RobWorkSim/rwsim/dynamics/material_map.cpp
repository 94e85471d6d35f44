#include "rwsim/dynamics/material_map.hpp"

#include <algorithm>
#include <utility>

namespace rwsim::dynamics {

double FrictionData::mu() const {
  if (parameters.empty() || parameters.front().second.empty()) return MaterialMap::kDefaultMu;
  return parameters.front().second.front();
}

bool MaterialMap::addMaterial(const std::string& name, const std::string& /*description*/) {
  if (hasMaterial(name)) return false;
  materials_.push_back(name);
  return true;
}

bool MaterialMap::hasMaterial(const std::string& name) const {
  return std::find(materials_.begin(), materials_.end(), name) != materials_.end();
}

bool MaterialMap::addObjectType(const std::string& name) {
  if (hasObjectType(name)) return false;
  objectTypes_.push_back(name);
  return true;
}

bool MaterialMap::hasObjectType(const std::string& name) const {
  return std::find(objectTypes_.begin(), objectTypes_.end(), name) != objectTypes_.end();
}

std::pair<std::string, std::string> MaterialMap::key(const std::string& a, const std::string& b) {
  return a < b ? std::make_pair(a, b) : std::make_pair(b, a);
}

void MaterialMap::setFriction(const std::string& a, const std::string& b, FrictionData data) {
  friction_[key(a, b)] = std::move(data);
}

const FrictionData* MaterialMap::friction(const std::string& a, const std::string& b) const {
  const auto it = friction_.find(key(a, b));
  return it == friction_.end() ? nullptr : &it->second;
}

double MaterialMap::mu(const std::string& a, const std::string& b) const {
  const FrictionData* data = friction(a, b);
  return data == nullptr ? kDefaultMu : data->mu();
}

void MaterialMap::setRestitution(const std::string& a, const std::string& b, double cr) {
  restitution_[key(a, b)] = cr;
}

double MaterialMap::restitution(const std::string& a, const std::string& b) const {
  const auto it = restitution_.find(key(a, b));
  return it == restitution_.end() ? 0.0 : it->second;
}

}  // namespace rwsim::dynamics
