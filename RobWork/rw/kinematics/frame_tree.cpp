#include "rw/kinematics/frame_tree.hpp"

#include <stdexcept>
#include <utility>

namespace rw::kinematics {

using rw::math::Transform3D;

namespace {

constexpr int kMovableStateSize = 7;

int stateSizeOf(const FrameSpec& spec) {
  switch (spec.type) {
    case FrameType::kMovable:
      return kMovableStateSize;
    case FrameType::kRevolute:
    case FrameType::kPrismatic:
      return spec.dependency ? 0 : 1;
    case FrameType::kFixed:
      return 0;
  }
  return 0;
}

}  // namespace

FrameTree::FrameTree() {
  FrameSpec world;
  world.name = std::string(kWorldName);
  frames_.emplace_back(std::move(world), kWorld, -1, 0, -1);
  children_.emplace_back();
  byName_.emplace(std::string(kWorldName), kWorld);
}

FrameId FrameTree::add(FrameSpec spec) {
  if (spec.name.empty()) throw std::invalid_argument("frame name is empty");
  if (byName_.count(spec.name) != 0) {
    throw std::invalid_argument("frame \"" + spec.name + "\" already exists");
  }
  if (!spec.parent.valid() || static_cast<std::size_t>(spec.parent.index) >= frames_.size()) {
    throw std::invalid_argument("frame \"" + spec.name + "\": parent is not in the tree");
  }
  int ownerOffset = -1;
  if (spec.dependency) {
    if (spec.type != FrameType::kRevolute && spec.type != FrameType::kPrismatic) {
      throw std::invalid_argument("frame \"" + spec.name +
                                  "\": only revolute and prismatic joints can depend on a joint");
    }
    const FrameId owner = spec.dependency->owner;
    if (!owner.valid() || static_cast<std::size_t>(owner.index) >= frames_.size()) {
      throw std::invalid_argument("joint \"" + spec.name +
                                  "\": its owner joint is not in the tree");
    }
    const Frame& ownerFrame = frame(owner);
    if (!ownerFrame.isJoint() || ownerFrame.isDependent()) {
      throw std::invalid_argument("joint \"" + spec.name + "\" depends on \"" + ownerFrame.name() +
                                  "\", which is not an independent joint");
    }
    ownerOffset = ownerFrame.stateOffset();
  }
  const int size = stateSizeOf(spec);
  const FrameId id{static_cast<std::int32_t>(frames_.size())};
  const FrameId parent = spec.parent;
  std::string name = spec.name;
  frames_.emplace_back(std::move(spec), id, size > 0 ? stateSize_ : -1, size, ownerOffset);
  stateSize_ += size;
  children_.emplace_back();
  children_[static_cast<std::size_t>(parent.index)].push_back(id);
  byName_.emplace(std::move(name), id);
  return id;
}

FrameId FrameTree::find(std::string_view name) const {
  const auto it = byName_.find(std::string(name));
  return it == byName_.end() ? FrameId{} : it->second;
}

State FrameTree::makeState() const {
  std::vector<FrameId> parents;
  parents.reserve(frames_.size());
  for (const Frame& f : frames_) parents.push_back(f.parent());
  State state(static_cast<std::size_t>(stateSize_), std::move(parents));
  for (const Frame& f : frames_) {
    if (f.type() == FrameType::kMovable) f.setMovableTransform(state, f.fixedTransform());
  }
  return state;
}

FKTable::FKTable(const FrameTree& tree, const State& state) : world_(tree.size()) {
  // Frames are in topological order for their static parents; a re-attached DAF may point to a
  // later frame, so those are resolved in a second pass by walking up.
  std::vector<char> done(tree.size(), 0);
  world_[0] = Transform3D::Identity();
  done[0] = 1;
  bool deferred = false;
  for (std::size_t i = 1; i < tree.size(); ++i) {
    const FrameId id{static_cast<std::int32_t>(i)};
    const FrameId parent = state.parentOf(id);
    if (static_cast<std::size_t>(parent.index) < i &&
        done[static_cast<std::size_t>(parent.index)]) {
      world_[i] =
          world_[static_cast<std::size_t>(parent.index)] * tree.frame(id).localTransform(state);
      done[i] = 1;
    } else {
      deferred = true;
    }
  }
  if (!deferred) return;
  for (std::size_t i = 1; i < tree.size(); ++i) {
    if (!done[i])
      world_[i] =
          rw::kinematics::worldTransform(tree, state, FrameId{static_cast<std::int32_t>(i)});
  }
}

Transform3D worldTransform(const FrameTree& tree, const State& state, FrameId frame) {
  Transform3D X = Transform3D::Identity();
  for (FrameId f = frame; f.index > 0; f = state.parentOf(f)) {
    X = tree.frame(f).localTransform(state) * X;
  }
  return X;
}

Transform3D relativeTransform(const FrameTree& tree, const State& state, FrameId from, FrameId to) {
  return worldTransform(tree, state, from).inverse() * worldTransform(tree, state, to);
}

}  // namespace rw::kinematics
