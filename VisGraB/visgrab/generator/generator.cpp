#include "visgrab/generator/generator.hpp"

#include <array>
#include <chrono>
#include <exception>
#include <map>
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <stdexcept>

#include "rw/common/stop_signals.hpp"
#include "rw/common/task_pool.hpp"
#include "rw/common/write_error.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "visgrab/database/atomic_file.hpp"
#include "visgrab/database/database_writer.hpp"
#include "visgrab/database/stereo_calibration.hpp"
#include "visgrab/generator/camera_model.hpp"
#include "visgrab/generator/scene_model.hpp"
#include "visgrab/generator/scene_products.hpp"
#include "visgrab/objects/object_spec.hpp"
#include "visgrab/objects/object_writer.hpp"
#include "visgrab/render/offscreen_renderer.hpp"

namespace visgrab::generator {

namespace {

namespace fs = std::filesystem;
using rw::math::Transform3D;
using rw::math::Vector3D;

/// Instance ids in the rendered id images: the table, then 10 + object id.
constexpr std::uint16_t kTableInstance = 1;
constexpr std::uint16_t kObjectInstanceBase = 10;

/// The generated models every worker reads (const after preparation).
struct Assets {
  std::map<int, objects::ObjectModel> objects;
  std::map<std::string, objects::TableModel> tables;
  /// The same meshes as shared pointers, for uploading.
  std::map<int, std::vector<std::shared_ptr<const visual::VisualMesh>>> objectMeshes;
  /// Each mesh's material class (VisualPart::material), parallel to objectMeshes.
  std::map<int, std::vector<std::optional<objects::SurfaceMaterial>>> objectMaterials;
  std::map<std::string, std::shared_ptr<const visual::VisualMesh>> tableMeshes;
};

Assets prepareAssets(const std::vector<database::SceneConditions>& scenes,
                     const GeneratorOptions& options, const AssetLayout& layout) {
  const objects::ObjectDatabaseSpec spec = objects::loadObjectSpecs(options.objectSpec);
  std::optional<objects::ObjectDatabaseSpec> tableSpec;  // read when `spec` lacks a table
  Assets assets;
  for (const auto& scene : scenes) {
    for (const int id : scene.objects) {
      if (assets.objects.count(id) != 0) continue;
      const objects::ObjectSpec* objectSpec = spec.findObject(id);
      if (objectSpec == nullptr) {
        throw std::runtime_error(options.objectSpec.string() + ": no object with id " +
                                 std::to_string(id));
      }
      objects::ObjectModel model = objects::generateObject(*objectSpec);
      objects::writeObjectFiles(model, options.out / layout.objects);
      auto& meshes = assets.objectMeshes[id];
      auto& materials = assets.objectMaterials[id];
      for (const auto& part : model.visual) {
        meshes.push_back(std::make_shared<const visual::VisualMesh>(part.mesh));
        materials.push_back(part.material);
      }
      assets.objects.emplace(id, std::move(model));
    }
    const std::string texture(database::toString(scene.texture));
    if (assets.tables.count(texture) == 0) {
      const objects::TableSpec* tableSpecOf = spec.findTable(texture);
      if (tableSpecOf == nullptr && !options.tableSpec.empty()) {
        if (!tableSpec) tableSpec = objects::loadObjectSpecs(options.tableSpec);
        tableSpecOf = tableSpec->findTable(texture);
      }
      if (tableSpecOf == nullptr) {
        throw std::runtime_error(options.objectSpec.string() + ": no table named \"" + texture +
                                 "\"");
      }
      objects::TableModel table = objects::generateTable(*tableSpecOf);
      objects::writeTableFiles(table, options.out / layout.tables);
      assets.tableMeshes[texture] = std::make_shared<const visual::VisualMesh>(table.surface);
      assets.tables.emplace(texture, std::move(table));
    }
  }
  copyHandFolder(options.handFolder, options.out / layout.hand);
  copyFile(options.materials, options.out / layout.materials);
  return assets;
}

/// One worker's renderer with the meshes it has uploaded.
class SceneRenderer {
 public:
  SceneRenderer(const Assets& assets, const CameraProfile& profile)
      : assets_(&assets), profile_(&profile) {}

  /// Renders the scene; `depthAndIds` also the ground truth (the colour is the same either way).
  render::RenderResult render(const database::SceneConditions& scene,
                              const std::vector<Transform3D>& X_WO,
                              const render::PinholeCamera& camera, bool depthAndIds) {
    render::Scene drawn;
    const std::string texture(database::toString(scene.texture));
    drawn.items.push_back({tableHandle(texture), Transform3D::Identity(), kTableInstance});
    for (std::size_t i = 0; i < scene.objects.size(); ++i) {
      const int id = scene.objects[i];
      const auto& handles = objectHandles(id);
      const auto& materials = assets_->objectMaterials.at(id);
      for (std::size_t k = 0; k < handles.size(); ++k) {
        render::SceneItem item{handles[k], X_WO[i],
                               static_cast<std::uint16_t>(kObjectInstanceBase + id)};
        for (const MaterialFinish& finish : profile_->materials) {
          if (materials[k] == finish.material) {
            item.specular = finish.specular;
            item.shininess = finish.shininess;
          }
        }
        drawn.items.push_back(item);
      }
    }
    drawn.background = Eigen::Vector3f(0.55f, 0.57f, 0.6f);  // a grey lab wall
    drawn.lighting.ambient = Eigen::Vector3f(0.3f, 0.3f, 0.3f);
    render::Light key;
    key.direction_W = Vector3D(0.35, 0.45, -1.0);
    key.colour = Eigen::Vector3f(0.75f, 0.74f, 0.7f);
    key.castsShadows = true;
    render::Light fill;
    fill.direction_W = Vector3D(-0.6, 0.2, -0.7);
    fill.colour = Eigen::Vector3f(0.2f, 0.21f, 0.23f);
    drawn.lighting.lights = {key, fill};
    for (const ExtraLight& extra : profile_->lights) {
      render::Light light;
      light.direction_W = Vector3D(extra.direction[0], extra.direction[1], extra.direction[2]);
      light.colour =
          Eigen::Vector3d(extra.colour[0], extra.colour[1], extra.colour[2]).cast<float>();
      drawn.lighting.lights.push_back(light);
    }
    render::RenderOptions options;
    options.depthAndIds = depthAndIds;
    return renderer_.render(drawn, camera, options);
  }

 private:
  render::MeshHandle tableHandle(const std::string& texture) {
    auto it = tables_.find(texture);
    if (it == tables_.end()) {
      it = tables_.emplace(texture, renderer_.add(assets_->tableMeshes.at(texture))).first;
    }
    return it->second;
  }

  const std::vector<render::MeshHandle>& objectHandles(int id) {
    auto it = objects_.find(id);
    if (it == objects_.end()) {
      std::vector<render::MeshHandle> handles;
      for (const auto& mesh : assets_->objectMeshes.at(id)) handles.push_back(renderer_.add(mesh));
      it = objects_.emplace(id, std::move(handles)).first;
    }
    return it->second;
  }

  const Assets* assets_;
  const CameraProfile* profile_;
  render::OffscreenRenderer renderer_;
  std::map<std::string, render::MeshHandle> tables_;
  std::map<int, std::vector<render::MeshHandle>> objects_;
};

bool onTable(const Transform3D& X_WO, const TableGeometry& table) {
  const Vector3D p = X_WO.translation();
  return p.z() > -0.01 && std::abs(p.x()) < 0.5 * table.x && std::abs(p.y()) < 0.5 * table.y;
}

/// What a scene's stereo images leave for the files that derive from them.
struct StereoImages {
  /// The rectified left and right images (BGR), as written.
  std::array<cv::Mat, 2> rectified;
  /// Depth and instance ids of the rectified left view.
  render::RenderResult truth;
};

/// Renders and writes the raw and rectified pair of a settled scene (record.files names them;
/// raw files it leaves empty are named raw_left.png/raw_right.png beside left.png) and renders
/// the ground truth of the rectified left view.
StereoImages writeStereoImages(const database::SceneConditions& scene,
                               const std::vector<Transform3D>& settled,
                               const GeneratorOptions& options, const CameraRig& rig,
                               database::DatabaseWriter& writer, SceneRenderer& renderer,
                               database::SceneRecord& record) {
  const bool direct = rig.profile().alreadyRectified();
  // Already rectified and without a mosaic, the raw images are the rectified ones: one file
  // each. Otherwise, until the index names the raw pair, it goes beside the rectified one.
  const bool rawIsRectified = direct && rig.profile().bayer == BayerPattern::kNone;
  const std::string sceneFolder = record.files.left.substr(0, record.files.left.rfind('/') + 1);
  if (rawIsRectified) {
    record.files.rawLeft = record.files.left;
    record.files.rawRight = record.files.right;
  } else {
    if (record.files.rawLeft.empty()) record.files.rawLeft = sceneFolder + "raw_left.png";
    if (record.files.rawRight.empty()) record.files.rawRight = sceneFolder + "raw_right.png";
  }
  StereoImages images;
  for (int side = 0; side < 2; ++side) {
    const std::string& file = side == 0 ? record.files.left : record.files.right;
    const std::string& rawFile = side == 0 ? record.files.rawLeft : record.files.rawRight;
    // Already rectified, the left render is the rectified left view: its depth and ids are
    // the ground truth.
    render::RenderResult image =
        renderer.render(scene, settled, rig.renderCamera(side), direct && side == 0);
    // The noise stream is keyed by the rectified image's file, as before raw images existed.
    Random noise(options.seed, record.id + "|" + file);
    const cv::Mat raw = rig.rawImage(side, image.colour, noise);
    // Sensor noise leaves string matching nothing to find: Huffman coding only.
    if (!rawIsRectified) {
      database::writeImageAtomically(writer.path(rawFile), raw,
                                     database::PngCompression::kHuffmanOnly);
    }
    auto& rectified = images.rectified[static_cast<std::size_t>(side)];
    rectified = rig.rectify(side, raw);
    database::writeImageAtomically(writer.path(file), rectified,
                                   database::PngCompression::kHuffmanOnly);
    if (direct && side == 0) images.truth = std::move(image);
  }
  if (!direct) images.truth = renderer.render(scene, settled, rig.rectifiedCamera(0), true);
  return images;
}

/// Makes one scene's files and returns its index record. @throws std::runtime_error when no
/// placement settles.
database::SceneRecord makeScene(const database::SceneConditions& scene, const Assets& assets,
                                const GeneratorOptions& options, const AssetLayout& layout,
                                const CameraRig& rig, database::DatabaseWriter& writer,
                                SceneRenderer& renderer) {
  database::SceneRecord record;
  record.id = database::sceneIdOf(scene, options.catalog);
  record.conditions = scene;
  record.files = writer.filesFor(record.id);
  const fs::path wcFile = writer.path(record.files.workcell);
  const fs::path dwcFile = writer.path(record.files.dynamicWorkcell);
  const fs::path folder = wcFile.parent_path();
  fs::create_directories(folder);
  const std::string toDatabase = relativeFolder(folder, writer.directory());
  std::vector<const objects::ObjectModel*> models;
  std::vector<std::string> names;
  for (const int id : scene.objects) {
    models.push_back(&assets.objects.at(id));
    names.push_back(models.back()->name);
  }
  TableGeometry table;
  table.x = assets.tables.at(std::string(database::toString(scene.texture))).x;
  table.y = assets.tables.at(std::string(database::toString(scene.texture))).y;

  database::writeFileAtomically(
      dwcFile, sceneDynamicsXml(scene, models, wcFile.filename().string(), toDatabase, layout));
  std::string reasons;
  std::vector<Transform3D> settled;
  for (int attempt = 0; attempt < options.maxAttempts && settled.empty(); ++attempt) {
    Placement placement = placeObjects(scene, models, options.seed, attempt, options.placement);
    for (auto& X : placement.X_TO) X.pretranslate(Vector3D(0.0, 0.0, options.dropHeight));
    const std::string wcXml =
        sceneWorkcellXml(scene, models, placement.X_TO, toDatabase, layout, table);
    database::writeFileAtomically(wcFile, wcXml);
    const auto dwc = rwsim::loaders::loadDynamicWorkCell(dwcFile);
    SettleResult result = settle(*dwc, names, options.settle);
    if (result.failure.empty() && !result.atRest && options.rollingDamping > 0.0) {
      const auto damped = rwsim::loaders::loadDynamicWorkCellFromStrings(
          sceneDynamicsXml(scene, models, wcFile.filename().string(), toDatabase, layout,
                           options.rollingDamping),
          wcXml, dwcFile);
      result = settle(*damped, names, options.settle);
    }
    std::string why;
    if (!result.failure.empty()) {
      why = "simulation failed: " + result.failure;
    } else if (!result.atRest) {
      why = "not at rest after " + std::to_string(result.time) + " s";
    } else if (result.maxPenetration > options.maxPenetration) {
      why = "penetration " + std::to_string(result.maxPenetration * 1000.0) + " mm";
    } else if (!std::all_of(result.X_WO.begin(), result.X_WO.end(),
                            [&](const Transform3D& X) { return onTable(X, table); })) {
      why = "an object left the table";
    }
    if (why.empty()) {
      settled = result.X_WO;
    } else {
      reasons +=
          (reasons.empty() ? "" : "; ") + ("attempt " + std::to_string(attempt + 1) + ": " + why);
    }
  }
  if (settled.empty()) throw std::runtime_error("no placement settled (" + reasons + ")");
  database::writeFileAtomically(
      wcFile, sceneWorkcellXml(scene, models, settled, toDatabase, layout, table));

  const StereoImages images =
      writeStereoImages(scene, settled, options, rig, writer, renderer, record);
  if (options.truthObserver) options.truthObserver(record.id, images.truth);
  const database::StereoCalibration& calibration = rig.calibration();
  database::writeCalibration(writer.path(record.files.calibration), calibration);
  std::vector<TruthObject> truthObjects;
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    truthObjects.push_back({scene.objects[i], names[i],
                            static_cast<std::uint16_t>(kObjectInstanceBase + scene.objects[i]),
                            settled[i]});
  }
  writeSceneProducts(images.rectified[0], images.rectified[1], calibration, images.truth,
                     kTableInstance, truthObjects, record.files, writer);
  for (std::size_t i = 0; i < scene.objects.size(); ++i) {
    record.objects.push_back({scene.objects[i], settled[i]});
  }
  return record;
}

}  // namespace

GenerationReport generateDatabase(const std::vector<database::SceneConditions>& scenes,
                                  const GeneratorOptions& options,
                                  const std::function<void(const GenerationProgress&)>& progress) {
  const auto start = std::chrono::steady_clock::now();
  database::DatabaseWriter writer(options.out, options.seed, "visgrab db generate", options.catalog,
                                  options.camera.name);
  const std::vector<database::SceneConditions> todo = writer.remaining(scenes);
  GenerationReport report;
  report.skipped = static_cast<int>(scenes.size() - todo.size());
  if (todo.empty()) return report;
  const AssetLayout layout;
  const CameraRig rig(options.camera);
  const Assets assets = prepareAssets(todo, options, layout);

  std::mutex mutex;
  GenerationProgress state;
  state.total = static_cast<int>(todo.size());
  state.skipped = report.skipped;
  const rw::common::TaskPool pool(std::min<int>(options.threads, static_cast<int>(todo.size())),
                                  options.stop);
  // One renderer per worker, made by its first scene (no OpenGL is fatal: the task throws).
  std::vector<std::unique_ptr<SceneRenderer>> renderers(static_cast<std::size_t>(pool.threads()));
  const std::size_t finished = pool.run(
      todo.size(),
      [&](std::size_t i, int worker) {
        auto& renderer = renderers[static_cast<std::size_t>(worker)];
        if (!renderer) renderer = std::make_unique<SceneRenderer>(assets, rig.profile());
        std::string failure;
        try {
          database::SceneRecord record =
              makeScene(todo[i], assets, options, layout, rig, writer, *renderer);
          writer.addScene(record);
        } catch (const rw::common::WriteError&) {
          throw;  // disk full, folder gone: the other scenes would fail the same way
        } catch (const std::exception& e) {
          failure = database::sceneIdOf(todo[i], options.catalog) + ": " + e.what();
        }
        const std::lock_guard lock(mutex);
        if (failure.empty()) {
          ++report.generated;
        } else {
          report.failures.push_back(failure);
        }
        ++state.done;
        state.lastId = database::sceneIdOf(todo[i], options.catalog);
        state.elapsed =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        if (progress) progress(state);
      },
      [&](int worker) { renderers[static_cast<std::size_t>(worker)].reset(); });
  if (finished < todo.size()) {
    throw rw::common::StopRequested("generation stopped after " + std::to_string(finished) +
                                    " of " + std::to_string(todo.size()) +
                                    " scenes; running it again continues it");
  }
  std::sort(report.failures.begin(), report.failures.end());
  return report;
}

}  // namespace visgrab::generator
