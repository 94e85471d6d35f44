#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rw/common/diagnostic.hpp"
#include "visgrab/database/scene_set.hpp"

namespace visgrab::database {

/// One <scene> of an original VisGraB benchmark manifest (visgrab-formats.md §1).
struct OriginalScene {
  /// scene/@id (surrounding whitespace removed).
  std::string id;
  /// info/sceneLocator.
  std::string sceneLocator;
  /// info/sceneSet.
  std::string sceneSet;
  /// info/sceneSetID.
  std::string sceneSetId;
  /// info/textureCondition.
  std::string textureCondition;
  /// input/leftImg, resolved against the manifest's folder.
  std::filesystem::path leftImage;
  /// input/rightImg, resolved.
  std::filesystem::path rightImage;
  /// input/disp, resolved.
  std::filesystem::path disparity;
  /// input/pointCloud, resolved.
  std::filesystem::path pointCloud;
  /// simulator/wc, resolved.
  std::filesystem::path workcell;
  /// simulator/dwc, resolved.
  std::filesystem::path dynamicWorkcell;
  /// simulator/collision, resolved; empty if the element is absent or empty.
  std::filesystem::path collision;
  /// Line of the <scene> element.
  int line = 0;
};

/// An original VisGraB benchmark manifest (type GraspUnknownObject).
struct OriginalManifest {
  /// Absolute folder of the manifest; relative paths in it are resolved against it.
  std::filesystem::path directory;
  /// Every <scene> in document order, duplicates included.
  std::vector<OriginalScene> scenes;
  /// Warnings: ignored elements, later <benchmark> elements, duplicate ids.
  std::vector<rw::common::Diagnostic> warnings;

  /// The scene with `id` (the last one with that id, as in the original); null if none.
  const OriginalScene* find(std::string_view id) const;
};

/// Reads an original manifest the way VisGraB's own reader did: namespace prefixes of elements
/// and attributes are ignored (undeclared prefixes too), the first <benchmark> of the root
/// <visgrab> is used and must have type GraspUnknownObject, every <scene> child is a scene,
/// a single child is looked up as the first one with its name, unknown elements are ignored
/// (with a warning), duplicate ids are kept and lookups find the last, paths are relative to
/// the manifest's folder. A missing required element fails the whole file. Deliberate
/// differences: ids and paths are trimmed, absolute paths are used as they are, <collision> is
/// optional. @throws rw::common::LoadError with file:line diagnostics.
OriginalManifest readOriginalManifest(const std::filesystem::path& file);

/// Same as readOriginalManifest, from text; `file` names it in messages and gives the folder
/// that paths are relative to. @throws rw::common::LoadError.
OriginalManifest parseOriginalManifest(std::string_view text, const std::filesystem::path& file);

/// The conditions of an original scene, derived from its locator, id, sceneSet and
/// textureCondition: first as an original folder id (`textured/cocacola/img_03`, also at the end
/// of a longer locator) or one of our ids; otherwise from the words in locator and id (object
/// names, last number 1..8 as pose) with the texture from textureCondition ("textured" or
/// "non-textured"/"nontextured"/"plain") and a sceneSet that must agree (single/double) if
/// given. nullopt when they cannot be derived unambiguously.
std::optional<SceneConditions> deriveConditions(const OriginalScene& scene);

}  // namespace visgrab::database
