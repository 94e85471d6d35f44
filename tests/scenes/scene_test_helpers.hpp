#pragma once

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

#include "rw/kinematics/frame_tree.hpp"
#include "rw/loaders/workcell_loader.hpp"
#include "rw/models/workcell.hpp"
#include "support/test_support.hpp"

/// Small helpers shared by the scene tests (hand models, workcell writer).
namespace visgrab::test::scenes {

/// The project's SDH model.
inline std::filesystem::path projectSdhFile() {
  return sourceDir() / "scenes" / "hands" / "sdh" / "sdh.wc.xml";
}

/// The project's PG70 model.
inline std::filesystem::path projectPg70File() {
  return sourceDir() / "scenes" / "hands" / "pg70" / "pg70.wc.xml";
}

/// Loads a workcell; a LoadError escapes with its file:line messages and fails the test.
inline std::unique_ptr<rw::models::WorkCell> load(const std::filesystem::path& file) {
  return rw::loaders::loadWorkCell(file);
}

/// The id of the frame `name`. @throws std::runtime_error if there is none.
inline rw::kinematics::FrameId frameOf(const rw::models::WorkCell& wc, std::string_view name) {
  const rw::kinematics::FrameId id = wc.findFrame(name);
  if (!id.valid()) throw std::runtime_error("no frame \"" + std::string(name) + "\"");
  return id;
}

/// The device `name`. @throws std::runtime_error if there is none.
inline const rw::models::Device& deviceOf(const rw::models::WorkCell& wc, std::string_view name) {
  const rw::models::Device* device = wc.findDevice(name);
  if (device == nullptr) throw std::runtime_error("no device \"" + std::string(name) + "\"");
  return *device;
}

/// X_W_frame of the frame `name` in `state`.
inline rw::math::Transform3D worldPose(const rw::models::WorkCell& wc,
                                       const rw::kinematics::State& state, std::string_view name) {
  return rw::kinematics::worldTransform(wc.frames(), state, frameOf(wc, name));
}

}  // namespace visgrab::test::scenes
