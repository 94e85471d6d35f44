#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>

#include "objects_test_support.hpp"
#include "rw/geometry/mesh_loader.hpp"
#include "rw/loaders/workcell_loader.hpp"
#include "rwsim/loaders/dynamic_workcell_loader.hpp"
#include "visgrab/objects/object_writer.hpp"

namespace {

namespace fs = std::filesystem;
using visgrab::objects::ObjectFiles;
using visgrab::objects::ObjectModel;
using namespace visgrab::test::objects;

std::string readBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// Number of triangles of `a` without a partner in `b` (same corners in the same cyclic order,
// each coordinate within `tol`); 0 when both hold the same triangles. Partners are looked up by
// their lexicographically smallest corner in a grid of 1 mm cells.
int unmatchedTriangles(const std::vector<Triangle>& a, const std::vector<Triangle>& b,
                       double tol = 1e-7) {
  using Cell = std::array<std::int64_t, 3>;
  auto turned = [](const Triangle& t) {
    int first = 0;
    for (int i = 1; i < 3; ++i) {
      if (std::lexicographical_compare(t[i].data(), t[i].data() + 3, t[first].data(),
                                       t[first].data() + 3)) {
        first = i;
      }
    }
    return Triangle{t[first], t[(first + 1) % 3], t[(first + 2) % 3]};
  };
  auto cell = [](const Eigen::Vector3d& p) {
    return Cell{std::llround(std::floor(p.x() * 1e3)), std::llround(std::floor(p.y() * 1e3)),
                std::llround(std::floor(p.z() * 1e3))};
  };
  std::multimap<Cell, Triangle> index;
  for (const Triangle& t : b) {
    const Triangle c = turned(t);
    index.emplace(cell(c[0]), c);
  }
  if (a.size() != b.size()) return static_cast<int>(std::max(a.size(), b.size()));
  int unmatched = 0;
  for (const Triangle& t : a) {
    const Triangle c = turned(t);
    const Cell home = cell(c[0]);
    bool found = false;
    for (int dx = -1; dx <= 1 && !found; ++dx) {
      for (int dy = -1; dy <= 1 && !found; ++dy) {
        for (int dz = -1; dz <= 1 && !found; ++dz) {
          auto [from, to] = index.equal_range({home[0] + dx, home[1] + dy, home[2] + dz});
          for (auto it = from; it != to; ++it) {
            if ((it->second[0] - c[0]).cwiseAbs().maxCoeff() <= tol &&
                (it->second[1] - c[1]).cwiseAbs().maxCoeff() <= tol &&
                (it->second[2] - c[2]).cwiseAbs().maxCoeff() <= tol) {
              index.erase(it);
              found = true;
              break;
            }
          }
        }
      }
    }
    if (!found) ++unmatched;
  }
  return unmatched;
}

// Indices of the collision pieces written as STL files (the box and handle pieces).
std::vector<std::size_t> meshPieces(const ObjectModel& model) {
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < model.collision.size(); ++k) {
    if (!model.collision[k].isRound()) out.push_back(k);
  }
  return out;
}

// All 18 objects written once into a temporary folder.
class WrittenObjects : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = std::make_unique<visgrab::test::TempDir>();
    for (const auto& model : projectModels()) {
      files_.push_back(visgrab::objects::writeObjectFiles(model, dir_->path() / "objects"));
    }
  }
  static void TearDownTestSuite() {
    files_.clear();
    dir_.reset();
  }
  static inline std::unique_ptr<visgrab::test::TempDir> dir_;
  static inline std::vector<ObjectFiles> files_;
};

TEST_F(WrittenObjects, WritesTheFilesOfEveryObject) {
  ASSERT_EQ(files_.size(), 18u);
  for (std::size_t i = 0; i < files_.size(); ++i) {
    const auto& f = files_[i];
    const auto& model = projectModels()[i];
    EXPECT_EQ(f.folder, dir_->path() / "objects" / model.name);
    for (const auto& p : {f.obj, f.mtl, f.workcell, f.dynamics})
      EXPECT_TRUE(fs::is_regular_file(p)) << p;
    EXPECT_EQ(f.textures.size(), model.visual.size());
    const auto pieces = meshPieces(model);
    ASSERT_EQ(f.hulls.size(), pieces.size());
    for (std::size_t j = 0; j < f.hulls.size(); ++j) {
      const std::size_t k = pieces[j];
      EXPECT_EQ(f.hulls[j].filename(), model.name + "_hull" + std::to_string(k) + ".stl");
      // Binary STL: 80-byte header, count, 50 bytes per triangle.
      EXPECT_EQ(fs::file_size(f.hulls[j]),
                84 + 50 * model.collision[k].triangles->triangles.size());
    }
    EXPECT_NE(readBytes(f.mtl).find("map_Kd " + model.name + "_"), std::string::npos);
  }
}

TEST_F(WrittenObjects, AssimpReadsTheSameTriangles) {
  for (std::size_t i = 0; i < files_.size(); ++i) {
    const auto& model = projectModels()[i];
    const auto obj = rw::geometry::loadMesh(files_[i].obj);
    EXPECT_EQ(unmatchedTriangles(meshTriangles(*obj), visualTriangles(model)), 0) << model.name;
    const auto pieces = meshPieces(model);
    for (std::size_t j = 0; j < pieces.size(); ++j) {
      const auto stl = rw::geometry::loadMesh(files_[i].hulls[j]);
      const auto& piece = *model.collision[pieces[j]].triangles;
      EXPECT_EQ(unmatchedTriangles(meshTriangles(*stl), meshTriangles(piece)), 0)
          << model.name << " hull " << pieces[j];
    }
  }
}

TEST_F(WrittenObjects, ExampleFilesLoad) {
  for (std::size_t i = 0; i < files_.size(); ++i) {
    std::vector<rw::common::Diagnostic> warnings;
    try {
      const auto wc = rw::loaders::loadWorkCell(files_[i].workcell, &warnings);
      ASSERT_TRUE(wc);
      const auto dwc = rwsim::loaders::loadDynamicWorkCell(files_[i].dynamics, &warnings);
      ASSERT_TRUE(dwc);
      EXPECT_TRUE(dwc->findBody(projectModels()[i].name).valid());
    } catch (const rw::common::LoadError& e) {
      FAIL() << e.what();
    }
    for (const auto& w : warnings) ADD_FAILURE() << w.format();
  }
}

// A tiny scene per object: world, a fixed table box, the object standing on it; its dynamic
// workcell includes the project's material file.
TEST_F(WrittenObjects, SceneWithEachObjectLoadsInBothLoaders) {
  const fs::path materials = visgrab::test::sourceDir() / "scenes/materials.xml";
  for (std::size_t i = 0; i < files_.size(); ++i) {
    const ObjectModel& model = projectModels()[i];
    const auto& standing = model.restingPoses.front().X_TO;
    const std::string wcText =
        "<WorkCell name=\"Scene\">\n"
        "  <Frame name=\"Table\" refframe=\"WORLD\">\n"
        "    <RPY>0 0 0</RPY><Pos>0 0 0</Pos>\n"
        "    <Drawable name=\"Top\"><RPY>0 0 0</RPY><Pos>0 0 -0.025</Pos>"
        "<Box x=\"1.2\" y=\"0.8\" z=\"0.05\"/></Drawable>\n"
        "  </Frame>\n" +
        visgrab::objects::objectFrameXml(model, "objects/" + model.name + "/", "Table", standing) +
        "</WorkCell>\n";
    const fs::path wcFile =
        visgrab::test::writeFile(dir_->path() / ("scene_" + model.name + ".wc.xml"), wcText);
    const std::string dwcText = "<DynamicWorkcell workcell=\"" + wcFile.filename().string() +
                                "\">\n  <Gravity>0 0 -9.81</Gravity>\n  <Include file=\"" +
                                materials.string() +
                                "\"/>\n  <FixedBody frame=\"Table\"><MaterialID>Table</MaterialID>"
                                "</FixedBody>\n" +
                                visgrab::objects::objectBodyXml(model) + "</DynamicWorkcell>\n";
    const fs::path dwcFile =
        visgrab::test::writeFile(dir_->path() / ("scene_" + model.name + ".dwc.xml"), dwcText);
    std::vector<rw::common::Diagnostic> warnings;
    try {
      const auto wc = rw::loaders::loadWorkCell(wcFile, &warnings);
      const auto frame = wc->findFrame(model.name);
      const auto* object = wc->findObject(frame);
      ASSERT_NE(object, nullptr) << model.name;
      EXPECT_EQ(object->visual.size(), 1u);
      ASSERT_EQ(object->collision.size(), model.collision.size());
      for (std::size_t k = 0; k < model.collision.size(); ++k) {
        const auto& g = *object->collision[k].geometry;
        const auto& piece = model.collision[k];
        EXPECT_TRUE(g.isConvex()) << model.name << " " << k;
        EXPECT_EQ(g.type(), piece.geometry->type()) << model.name << " " << k;
        if (piece.isRound()) {
          EXPECT_EQ(g.parameters(), piece.geometry->parameters()) << model.name << " " << k;
          EXPECT_TRUE(piece.X_OG.isApprox(object->collision[k].X_frame_geometry, 1e-12))
              << model.name << " " << k;
        } else {
          EXPECT_EQ(
              unmatchedTriangles(meshTriangles(g.triangles()), meshTriangles(*piece.triangles)), 0);
        }
      }
      const auto dwc = rwsim::loaders::loadDynamicWorkCell(dwcFile, &warnings);
      const auto index = dwc->findBody(model.name);
      ASSERT_TRUE(index.valid()) << model.name;
      const auto& body = dwc->body(index);
      EXPECT_EQ(body.kind, rwsim::dynamics::BodyKind::kRigid);
      EXPECT_EQ(body.material, "Object");
      EXPECT_EQ(body.mass.mass, model.mass.mass);
      EXPECT_EQ(body.mass.cog, model.mass.cog);  // shortest round-trip text: exact
      EXPECT_EQ(body.mass.inertia, model.mass.inertia);
      // The loader's own estimate from the loaded (float) hulls agrees with ours.
      const std::string estimated = std::string(dwcText).replace(
          dwcText.find("<COG>"), dwcText.find("</Inertia>") + 10 - dwcText.find("<COG>"),
          "<EstimateInertia/>");
      const auto dwc2 = rwsim::loaders::loadDynamicWorkCellFromString(estimated, dwcFile);
      const auto& body2 = dwc2->body(dwc2->findBody(model.name));
      EXPECT_LT((body2.mass.cog - model.mass.cog).norm(), 1e-6) << model.name;
      EXPECT_LT((body2.mass.inertia - model.mass.inertia).norm(), 1e-5 * model.mass.inertia.norm())
          << model.name;
    } catch (const rw::common::LoadError& e) {
      FAIL() << e.what();
    }
    for (const auto& w : warnings) ADD_FAILURE() << w.format();
  }
}

TEST_F(WrittenObjects, CanWorkcellHoldsTrueCylinderAndFrusta) {
  using rw::geometry::GeometryType;
  const auto& objects = projectSpec().objects;
  const auto it = std::find_if(objects.begin(), objects.end(),
                               [](const auto& o) { return o.name == "cocacola"; });
  ASSERT_NE(it, objects.end());
  const auto& spec = *it;
  const auto& files = files_[static_cast<std::size_t>(it - objects.begin())];
  const std::string text = readBytes(files.workcell);
  EXPECT_NE(text.find("<Cylinder radius="), std::string::npos) << text;
  EXPECT_NE(text.find("<Custom type=\"Frustum\" param="), std::string::npos) << text;
  EXPECT_EQ(text.find(".stl"), std::string::npos) << text;
  EXPECT_TRUE(files.hulls.empty());
  std::vector<rw::common::Diagnostic> warnings;
  const auto wc = rw::loaders::loadWorkCell(files.workcell, &warnings);
  EXPECT_TRUE(warnings.empty());
  const auto* object = wc->findObject(wc->findFrame(spec.name));
  ASSERT_NE(object, nullptr);
  ASSERT_EQ(object->collision.size(), spec.profile.size() - 1);
  int cylinders = 0;
  int frusta = 0;
  for (std::size_t k = 0; k + 1 < spec.profile.size(); ++k) {
    const auto& p = spec.profile[k];
    const auto& q = spec.profile[k + 1];
    const auto& instance = object->collision[k];
    const auto& g = *instance.geometry;
    const double h = q.z - p.z;
    if (p.r == q.r) {
      ++cylinders;
      ASSERT_EQ(g.type(), GeometryType::kCylinder) << k;
      EXPECT_NEAR(g.parameters()[0], p.r, 1e-15) << k;
      EXPECT_NEAR(g.parameters()[1], h, 1e-15) << k;
    } else {
      ++frusta;
      ASSERT_EQ(g.type(), GeometryType::kFrustum) << k;
      EXPECT_NEAR(g.parameters()[0], p.r, 1e-15) << k;
      EXPECT_NEAR(g.parameters()[1], q.r, 1e-15) << k;
      EXPECT_NEAR(g.parameters()[2], h, 1e-15) << k;
    }
    // Centred on the segment: from the bottom (z = p.z) to the top (z = q.z) in the object.
    EXPECT_TRUE(instance.X_frame_geometry.linear().isIdentity(1e-12)) << k;
    EXPECT_NEAR(instance.X_frame_geometry.translation().z(), (p.z + q.z) / 2.0, 1e-15) << k;
    EXPECT_NEAR(instance.X_frame_geometry.translation().head<2>().norm(), 0.0, 1e-15) << k;
    EXPECT_NEAR(g.bounds().min.z() + instance.X_frame_geometry.translation().z(), p.z, 1e-12);
    EXPECT_NEAR(g.bounds().max.z() + instance.X_frame_geometry.translation().z(), q.z, 1e-12);
  }
  EXPECT_GE(cylinders, 1);
  EXPECT_GE(frusta, 1);
}

TEST(ObjectWriter, WritesIdenticalBytesEveryRun) {
  visgrab::test::TempDir a;
  visgrab::test::TempDir b;
  for (const auto& spec : projectSpec().objects) {
    visgrab::objects::writeObjectFiles(visgrab::objects::generateObject(spec), a.path());
    visgrab::objects::writeObjectFiles(visgrab::objects::generateObject(spec), b.path());
  }
  for (const auto& spec : projectSpec().tables) {
    visgrab::objects::writeTableFiles(visgrab::objects::generateTable(spec), a.path());
    visgrab::objects::writeTableFiles(visgrab::objects::generateTable(spec), b.path());
  }
  std::size_t files = 0;
  for (const auto& entry : fs::recursive_directory_iterator(a.path())) {
    if (!entry.is_regular_file()) continue;
    ++files;
    const fs::path other = b.path() / fs::relative(entry.path(), a.path());
    ASSERT_TRUE(fs::exists(other)) << other;
    EXPECT_TRUE(readBytes(entry.path()) == readBytes(other)) << entry.path();
  }
  EXPECT_GT(files, 18u * 6u);
}

TEST(ObjectWriter, TableFilesLoad) {
  visgrab::test::TempDir dir;
  for (const auto& spec : projectSpec().tables) {
    const auto table = visgrab::objects::generateTable(spec);
    const fs::path obj = visgrab::objects::writeTableFiles(table, dir.path());
    EXPECT_TRUE(fs::exists(obj.parent_path() / (spec.name + ".png")));
    const auto mesh = rw::geometry::loadMesh(obj);
    EXPECT_EQ(mesh->triangles.size(), table.surface.triangles.size());
  }
}

}  // namespace
