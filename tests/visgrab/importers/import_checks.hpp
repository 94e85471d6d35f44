#pragma once

#include <string>
#include <utility>

#include "visgrab/importers/grasp_importers.hpp"
#include "visgrab/importers/nd_array.hpp"

/// What the importers' tests share besides the files they write (test_files.hpp): the message
/// of a refused input and the jaw frame the grasps are imported for.
namespace visgrab::test {

/// The message of the importers::ImportError that `f` throws ("" when it throws none).
template <typename F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const importers::ImportError& e) {
    return e.what();
  }
  return "";
}

/// An import context for scene `sceneId` and method `method` with a Franka-like jaw frame built
/// in code: hand "franka", stroke 0.08 m, fingertips 0.01 m beyond the pad centre.
inline importers::ImportContext frankaImportContext(std::string sceneId, std::string method) {
  importers::ImportContext c;
  c.sceneId = std::move(sceneId);
  c.method = std::move(method);
  c.hand = "franka";
  c.jaw.stroke = 0.08;
  c.jaw.tipDepth = 0.01;
  return c;
}

}  // namespace visgrab::test
