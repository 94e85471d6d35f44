#include "visgrab/database/database.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <iterator>
#include <opencv2/core.hpp>
#include <string>

#include "rw/math/rpy.hpp"
#include "support/test_support.hpp"
#include "visgrab/database/atomic_file.hpp"
#include "visgrab/database/database_writer.hpp"

namespace visgrab::database {
namespace {

namespace fs = std::filesystem;
using rw::common::LoadError;

// Writes a tiny scene (8x6 images, ideal calibration, stub models) and records it.
void addFakeScene(DatabaseWriter& writer, const SceneConditions& c, int shade) {
  const std::string id = sceneIdOf(c);
  const SceneFiles files = writer.filesFor(id);
  cv::Mat left(6, 8, CV_8UC3, cv::Scalar(shade, 10, 200));
  cv::Mat right(6, 8, CV_8UC3, cv::Scalar(shade, 20, 100));
  writeImageAtomically(writer.path(files.left), left);
  writeImageAtomically(writer.path(files.right), right);
  writeCalibration(writer.path(files.calibration),
                   idealRectifiedRig(10, 10, 3.5, 2.5, 0.1, 8, 6,
                                     rw::math::makeTranslation(Eigen::Vector3d(0, -0.5, 0.6))));
  writeFileAtomically(writer.path(files.workcell), "<WorkCell name=\"s\"/>\n");
  writeFileAtomically(writer.path(files.dynamicWorkcell), "<DynamicWorkcell/>\n");
  // The files of index format 2, with values the tests below know.
  cv::Mat raw(6, 8, CV_8UC1, cv::Scalar(shade));
  writeImageAtomically(writer.path(files.rawLeft), raw);
  writeImageAtomically(writer.path(files.rawRight), raw);
  cv::Mat disparity(6, 8, CV_16UC1, cv::Scalar(0));
  disparity.at<std::uint16_t>(1, 2) = 40 * 256 + 64;  // 40.25 px
  writeImageAtomically(writer.path(files.disparity), disparity);
  cv::Mat depth(6, 8, CV_16UC1, cv::Scalar(6543));  // 0.6543 m
  depth.at<std::uint16_t>(0, 0) = 0;                // nothing drawn
  writeImageAtomically(writer.path(files.depth), depth);
  cv::Mat mask(6, 8, CV_8UC1, cv::Scalar(255));
  mask.at<std::uint8_t>(3, 4) = static_cast<std::uint8_t>(c.objects[0]);
  writeImageAtomically(writer.path(files.mask), mask);
  PointCloud cloud;
  cloud.points = {Eigen::Vector3f(0.1f, -0.2f, 0.65f), Eigen::Vector3f(0, 0, 1)};
  cloud.colours = {{1, 2, 3}, {255, 0, static_cast<std::uint8_t>(shade)}};
  cloud.comments = {"test cloud"};
  writeFileAtomically(writer.path(files.pointCloud), pointCloudToPly(cloud));
  writeFileAtomically(writer.path(files.poses), "%YAML:1.0\n---\nobjects: []\n");
  SceneRecord record{id, c, files, {}};
  for (int object : c.objects) {
    record.objects.push_back(
        {object, rw::math::rpyTransform(Eigen::Vector3d(0.2 * object, 0, 0),
                                        Eigen::Vector3d(0.01 * object, 0.02, 0.03))});
  }
  writer.addScene(record);
}

class DatabaseTest : public ::testing::Test {
 protected:
  void SetUp() override {
    DatabaseWriter writer(dir_.path(), 42, "test");
    addFakeScene(writer, SceneConditions::single(Texture::kTextured, 5, 3), 1);
    addFakeScene(writer, SceneConditions::single(Texture::kPlain, 5, 6), 2);
    addFakeScene(writer, SceneConditions::pairScene(Texture::kTextured, 'e', 7), 3);
  }
  test::TempDir dir_;
};

TEST_F(DatabaseTest, ListFilterAndShow) {
  const Database db = Database::open(dir_.path());
  EXPECT_EQ(db.source(), Database::Source::kGenerated);
  EXPECT_EQ(db.seed(), 42u);
  ASSERT_EQ(db.list().size(), 3u);
  EXPECT_EQ(db.list()[0].id, "plain/single/cocacola/06");
  EXPECT_EQ(db.list()[1].id, "textured/single/cocacola/03");
  EXPECT_EQ(db.list()[2].id, "textured/double/cocacola_saltcylinder/07");
  EXPECT_EQ(db.filter(SceneFilter::parse("textured")).size(), 2u);
  EXPECT_EQ(db.filter(SceneFilter::parse("lying;close")).size(), 2u);
  EXPECT_EQ(db.filter(SceneFilter::parse("object=14")).size(), 1u);
  EXPECT_EQ(Database::summaryLine(db.list()[1]),
            "textured/single/cocacola/03                   textured, single, standing, object 5 "
            "cocacola, pose 3");
  const std::string details = Database::details(db.scene("textured/single/cocacola/03"));
  EXPECT_NE(details.find("original id:      textured/cocacola/img_03\n"), std::string::npos);
  EXPECT_NE(details.find("object 5 cocacola: position 0.0500 0.0200 0.0300 m, RPY 57.30 0.00 "
                         "0.00 deg (table frame)"),
            std::string::npos)
      << details;
  // The original spelling finds the scene too.
  EXPECT_EQ(db.scene("textured/cocacola/img_03").id, "textured/single/cocacola/03");
  EXPECT_TRUE(Database::openAny(dir_.path() / "index.xml").contains("plain/single/cocacola/06"));
}

TEST_F(DatabaseTest, ImagesCalibrationAndGroundTruth) {
  const Database db = Database::open(dir_.path());
  const cv::Mat left = db.leftImage("textured/single/cocacola/03");
  ASSERT_EQ(left.rows, 6);
  ASSERT_EQ(left.cols, 8);
  EXPECT_EQ(left.at<cv::Vec3b>(2, 3), cv::Vec3b(1, 10, 200));
  EXPECT_EQ(db.rightImage("textured/single/cocacola/03").at<cv::Vec3b>(0, 0),
            cv::Vec3b(1, 20, 100));
  const StereoCalibration calibration = db.calibration("textured/single/cocacola/03");
  EXPECT_EQ(calibration.width, 8);
  EXPECT_NEAR(calibration.baseline(), 0.1, 1e-12);
  const auto& truth = db.groundTruth("textured/double/cocacola_saltcylinder/07");
  ASSERT_EQ(truth.size(), 2u);
  EXPECT_EQ(truth[1].object, 14);
  EXPECT_TRANSFORM_NEAR(
      truth[1].X_WO,
      rw::math::rpyTransform(Eigen::Vector3d(2.8, 0, 0), Eigen::Vector3d(0.14, 0.02, 0.03)),
      1e-9);  // the index holds 1e-9 degree
}

std::string fileBytes(const fs::path& file);

TEST_F(DatabaseTest, DisparityDepthMaskAndPointCloud) {
  const Database db = Database::open(dir_.path());
  const std::string id = "textured/double/cocacola_saltcylinder/07";
  const SceneEntry& e = db.scene(id);
  const fs::path folder = dir_.path() / "scenes" / id;
  EXPECT_EQ(e.rawLeftImage, folder / "raw_left.png");
  EXPECT_EQ(e.rawRightImage, folder / "raw_right.png");
  EXPECT_EQ(e.disparity, folder / "disparity.png");
  EXPECT_EQ(e.pointCloud, folder / "cloud.ply");
  EXPECT_EQ(e.depth, folder / "depth.png");
  EXPECT_EQ(e.mask, folder / "mask.png");
  EXPECT_EQ(e.poses, folder / "poses.yml");

  const cv::Mat disparity = db.disparityImage(id);
  ASSERT_EQ(disparity.type(), CV_32FC1);
  ASSERT_EQ(disparity.size(), cv::Size(8, 6));
  EXPECT_EQ(disparity.at<float>(1, 2), 40.25f);
  EXPECT_LT(disparity.at<float>(0, 0), 0.0f);  // none
  const cv::Mat depth = db.depthImage(id);
  ASSERT_EQ(depth.type(), CV_32FC1);
  EXPECT_NEAR(depth.at<float>(5, 7), 0.6543, 1e-7);
  EXPECT_EQ(depth.at<float>(0, 0), 0.0f);
  const cv::Mat mask = db.instanceMask(id);
  ASSERT_EQ(mask.type(), CV_8UC1);
  EXPECT_EQ(mask.at<std::uint8_t>(3, 4), 5);
  EXPECT_EQ(mask.at<std::uint8_t>(0, 0), 255);
  const PointCloud cloud = db.pointCloud(id);
  ASSERT_EQ(cloud.points.size(), 2u);
  EXPECT_EQ(cloud.points[0], Eigen::Vector3f(0.1f, -0.2f, 0.65f));
  EXPECT_EQ(cloud.colours[1], (std::array<std::uint8_t, 3>{255, 0, 3}));
  EXPECT_EQ(cloud.comments, std::vector<std::string>{"test cloud"});
}

TEST_F(DatabaseTest, ShowListsEveryFile) {
  const Database db = Database::open(dir_.path());
  const std::string details = Database::details(db.scene("plain/single/cocacola/06"));
  for (const char* name : {"raw_left.png", "raw_right.png", "left.png", "right.png",
                           "calibration.yml", "disparity.png", "cloud.ply", "depth.png", "mask.png",
                           "poses.yml", "scene.wc.xml", "scene.dwc.xml"}) {
    EXPECT_NE(details.find(std::string("/plain/single/cocacola/06/") + name + "\n"),
              std::string::npos)
        << name << " in\n"
        << details;
  }
  fs::remove(dir_.path() / "scenes/plain/single/cocacola/06/cloud.ply");
  EXPECT_NE(Database::details(db.scene("plain/single/cocacola/06"))
                .find("point cloud:      " +
                      (dir_.path() / "scenes/plain/single/cocacola/06/cloud.ply").string() +
                      "  (missing)\n"),
            std::string::npos);
}

TEST_F(DatabaseTest, BadProductFilesNameTheFileAndWhatWasExpected) {
  const Database db = Database::open(dir_.path());
  const std::string id = "textured/single/cocacola/03";
  const fs::path folder = dir_.path() / "scenes" / id;
  // An 8-bit depth image and a 16-bit mask are the wrong types.
  writeImageAtomically(folder / "depth.png", cv::Mat(6, 8, CV_8UC1, cv::Scalar(3)));
  try {
    db.depthImage(id);
    FAIL();
  } catch (const DatabaseError& e) {
    EXPECT_EQ(std::string(e.what()),
              (folder / "depth.png").string() + ": error: depth image of scene " + id +
                  ": expected a single-channel 16-bit PNG (0.1 mm units), found 1 channel(s) of "
                  "8-bit values");
  }
  writeImageAtomically(folder / "mask.png", cv::Mat(6, 8, CV_16UC1, cv::Scalar(3)));
  try {
    db.instanceMask(id);
    FAIL();
  } catch (const DatabaseError& e) {
    EXPECT_EQ(std::string(e.what()),
              (folder / "mask.png").string() + ": error: instance mask of scene " + id +
                  ": expected a single-channel 8-bit PNG (object ids), found 1 channel(s) of "
                  "16-bit values");
  }
  writeImageAtomically(folder / "disparity.png", cv::Mat(6, 8, CV_8UC3, cv::Scalar(3)));
  EXPECT_THROW(db.disparityImage(id), DatabaseError);
  // A truncated point cloud.
  const std::string ply = fileBytes(folder / "cloud.ply");
  writeFileAtomically(folder / "cloud.ply", std::string_view(ply).substr(0, ply.size() - 4));
  try {
    db.pointCloud(id);
    FAIL();
  } catch (const DatabaseError& e) {
    EXPECT_EQ(std::string(e.what()),
              (folder / "cloud.ply").string() +
                  ": error: the header announces 2 vertices of 15 bytes (30 bytes) but 26 bytes "
                  "follow it (truncated) (point cloud of scene " +
                  id + ")");
  }
  fs::remove(folder / "cloud.ply");
  EXPECT_THROW(db.pointCloud(id), DatabaseError);
}

TEST(OriginalManifestDatabase, ReadsTheManifestsDisparityAndListsItsFiles) {
  test::TempDir dir;
  const fs::path manifest = dir.path() / "benchmark.xml";
  writeFileAtomically(
      manifest,
      "<visgrab><benchmark type=\"GraspUnknownObject\"><scene id=\"cocacola_03\"><info>"
      "<sceneLocator>textured/cocacola/img_03</sceneLocator><sceneSet>single</sceneSet>"
      "<sceneSetID>1</sceneSetID><textureCondition>textured</textureCondition></info><input>"
      "<leftImg>l.png</leftImg><rightImg>r.png</rightImg><disp>d.png</disp>"
      "<pointCloud>pc.pcd</pointCloud></input><simulator><wc>s.wc.xml</wc><dwc>s.dwc.xml</dwc>"
      "</simulator></scene></benchmark></visgrab>\n");
  const Database db = Database::openOriginalManifest(manifest);
  const SceneEntry& e = db.scene("cocacola_03");
  EXPECT_EQ(e.disparity, dir.path() / "d.png");
  EXPECT_EQ(e.pointCloud, dir.path() / "pc.pcd");
  const std::string details = Database::details(e);
  EXPECT_NE(details.find("disparity:        " + (dir.path() / "d.png").string() + "  (missing)"),
            std::string::npos)
      << details;
  EXPECT_NE(details.find("point cloud:      " + (dir.path() / "pc.pcd").string()),
            std::string::npos)
      << details;
  // An 8-bit disparity is read as its value, a 16-bit one as value / 256; 0 is none.
  cv::Mat eight(2, 3, CV_8UC1, cv::Scalar(17));
  eight.at<std::uint8_t>(1, 2) = 0;
  writeImageAtomically(dir.path() / "d.png", eight);
  cv::Mat d = db.disparityImage("cocacola_03");
  EXPECT_EQ(d.at<float>(0, 0), 17.0f);
  EXPECT_LT(d.at<float>(1, 2), 0.0f);
  writeImageAtomically(dir.path() / "d.png", cv::Mat(2, 3, CV_16UC1, cv::Scalar(17 * 256 + 128)));
  d = db.disparityImage("cocacola_03");
  EXPECT_EQ(d.at<float>(1, 1), 17.5f);
  // The original's cloud format is not ours: the error names the file.
  writeFileAtomically(dir.path() / "pc.pcd", "# .PCD v0.7\nVERSION 0.7\n");
  try {
    db.pointCloud("cocacola_03");
    FAIL();
  } catch (const DatabaseError& error) {
    EXPECT_EQ(std::string(error.what()),
              (dir.path() / "pc.pcd").string() +
                  ": error: not a PLY file (it must start with the line \"ply\") (point cloud "
                  "of scene cocacola_03)");
  }
}

TEST_F(DatabaseTest, Version1DatabasesHaveNoProductFiles) {
  test::TempDir old;
  writeFileAtomically(old.path() / "index.xml",
                      "<VisGraBDatabase formatVersion=\"1\" seed=\"4\">\n"
                      "  <Scene id=\"plain/single/corny/07\" texture=\"plain\" kind=\"single\" "
                      "arrangement=\"lying\" pose=\"7\">\n"
                      "    <Files left=\"l.png\" right=\"r.png\" calibration=\"c.yml\" "
                      "workcell=\"s.wc.xml\" dynamicWorkcell=\"s.dwc.xml\"/>\n"
                      "    <Object id=\"6\" name=\"corny\"><Pos>0 0 0</Pos><RPY>0 0 0</RPY>"
                      "</Object>\n  </Scene>\n</VisGraBDatabase>\n");
  const Database db = Database::open(old.path());
  const SceneEntry& e = db.scene("plain/single/corny/07");
  EXPECT_TRUE(e.disparity.empty());
  EXPECT_TRUE(e.pointCloud.empty());
  EXPECT_TRUE(e.depth.empty());
  EXPECT_TRUE(e.rawLeftImage.empty());
  EXPECT_EQ(Database::details(e).find("depth"), std::string::npos);
  try {
    db.depthImage(e.id);
    FAIL();
  } catch (const DatabaseError& error) {
    EXPECT_EQ(std::string(error.what()), "scene plain/single/corny/07: no depth image is known");
  }
  // A writer does not resume it: its scenes lack the new files.
  try {
    DatabaseWriter writer(old.path(), 4);
    FAIL();
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find("generated in index format 1"), std::string::npos)
        << error.what();
  }
}

std::string fileBytes(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(WriteImageAtomically, HuffmanOnlyPngKeepsEveryPixel) {
  test::TempDir dir;
  DatabaseWriter writer(dir.path(), 7, "test");
  const SceneConditions c = SceneConditions::single(Texture::kPlain, 5, 1);
  SceneFiles files = writer.filesFor(sceneIdOf(c));
  // The five files of format version 1 only.
  files.rawLeft = files.rawRight = files.disparity = files.pointCloud = files.depth = files.mask =
      files.poses = "";
  // Sensor-like noise over a gradient: every pixel its own value.
  cv::Mat image(48, 64, CV_8UC3);
  cv::RNG rng(12345);
  rng.fill(image, cv::RNG::NORMAL, cv::Scalar::all(128), cv::Scalar::all(20));
  writeImageAtomically(writer.path(files.left), image, PngCompression::kHuffmanOnly);
  writeImageAtomically(writer.path(files.right), image, PngCompression::kBest);
  // Another encoding than level 9's (the option reached the encoder) ...
  EXPECT_NE(fileBytes(writer.path(files.left)), fileBytes(writer.path(files.right)));
  writeCalibration(
      writer.path(files.calibration),
      idealRectifiedRig(10, 10, 31.5, 23.5, 0.1, 64, 48, rw::math::Transform3D::Identity()));
  writeFileAtomically(writer.path(files.workcell), "<WorkCell name=\"s\"/>\n");
  writeFileAtomically(writer.path(files.dynamicWorkcell), "<DynamicWorkcell/>\n");
  writer.addScene({sceneIdOf(c), c, files, {{5, rw::math::Transform3D::Identity()}}});
  // ... and the same pixels through the database's reader.
  const Database db = Database::open(dir.path());
  for (const cv::Mat& read : {db.leftImage(sceneIdOf(c)), db.rightImage(sceneIdOf(c))}) {
    ASSERT_EQ(read.size(), image.size());
    ASSERT_EQ(read.type(), image.type());
    EXPECT_EQ(cv::norm(read, image, cv::NORM_INF), 0.0);
  }
}

TEST_F(DatabaseTest, UnknownIdSuggestsClosestIds) {
  const Database db = Database::open(dir_.path());
  try {
    db.scene("textured/single/cocacola/04");
    FAIL();
  } catch (const UnknownSceneError& e) {
    EXPECT_EQ(e.id(), "textured/single/cocacola/04");
    ASSERT_FALSE(e.closest().empty());
    EXPECT_EQ(e.closest()[0], "textured/single/cocacola/03");
    EXPECT_EQ(std::string(e.what()),
              "unknown scene id \"textured/single/cocacola/04\"; closest known ids: "
              "textured/single/cocacola/03 plain/single/cocacola/06 "
              "textured/double/cocacola_saltcylinder/07");
  }
  EXPECT_THROW(db.leftImage("nope"), UnknownSceneError);
}

TEST_F(DatabaseTest, MissingAndCorruptImagesNameTheFile) {
  const Database db = Database::open(dir_.path());
  const fs::path left = dir_.path() / "scenes/textured/single/cocacola/03/left.png";
  const fs::path right = dir_.path() / "scenes/textured/single/cocacola/03/right.png";
  fs::remove(left);
  try {
    db.leftImage("textured/single/cocacola/03");
    FAIL();
  } catch (const DatabaseError& e) {
    EXPECT_EQ(std::string(e.what()), left.string() +
                                         ": error: left image of scene "
                                         "textured/single/cocacola/03: no such file");
  }
  // Truncated PNG: keep only the first half of the file.
  std::string bytes;
  {
    std::ifstream in(right, std::ios::binary);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  ASSERT_GT(bytes.size(), 40u);
  writeFileAtomically(right, std::string_view(bytes).substr(0, bytes.size() / 2));
  try {
    db.rightImage("textured/single/cocacola/03");
    FAIL();
  } catch (const DatabaseError& e) {
    EXPECT_EQ(std::string(e.what()),
              right.string() +
                  ": error: right image of scene textured/single/cocacola/03: cannot decode the "
                  "image (corrupt, truncated or not an image)");
  }
  writeFileAtomically(right, "not a png");
  EXPECT_THROW(db.rightImage("textured/single/cocacola/03"), DatabaseError);
  // Found by fuzzing (fuzz/regressions/png): a header announcing 30000 x 30000 pixels made
  // OpenCV allocate 2.7 GB; it is refused before decoding.
  const std::string size30000 = {'\0', '\0', static_cast<char>(0x75), static_cast<char>(0x30)};
  bytes.replace(16, 4, size30000);
  bytes.replace(20, 4, size30000);
  writeFileAtomically(right, bytes);
  try {
    db.rightImage("textured/single/cocacola/03");
    FAIL();
  } catch (const DatabaseError& e) {
    EXPECT_EQ(std::string(e.what()),
              right.string() +
                  ": error: right image of scene textured/single/cocacola/03: the PNG announces "
                  "30000 x 30000 pixels, more than the 67108864 this reader accepts");
  }
}

TEST_F(DatabaseTest, MissingOrCorruptIndex) {
  test::TempDir empty;
  try {
    Database::open(empty.path());
    FAIL();
  } catch (const LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("index.xml: error: cannot read the database index: "),
              std::string::npos);
  }
  writeFileAtomically(empty.path() / "index.xml", "<VisGraBDatabase formatVersion=\"1\"");
  EXPECT_THROW(Database::open(empty.path()), LoadError);
}

TEST_F(DatabaseTest, WriterResumesAndKnowsCompleteScenes) {
  DatabaseWriter writer(dir_.path(), 42);
  EXPECT_TRUE(writer.resumed());
  EXPECT_EQ(writer.index().generator, "test");
  EXPECT_TRUE(writer.isComplete("textured/single/cocacola/03"));
  EXPECT_FALSE(writer.isComplete("textured/single/cocacola/04"));
  // A scene whose files are gone is no longer complete.
  fs::remove(dir_.path() / "scenes/plain/single/cocacola/06/scene.dwc.xml");
  EXPECT_FALSE(writer.isComplete("plain/single/cocacola/06"));
  const auto remaining = writer.remaining(enumerateScenes());
  EXPECT_EQ(remaining.size(), 432u - 2u);
  // Re-adding replaces the record; files must exist.
  SceneRecord record = writer.index().scenes.at(0);
  EXPECT_THROW(writer.addScene(record), std::runtime_error);
  addFakeScene(writer, SceneConditions::single(Texture::kPlain, 5, 6), 9);
  EXPECT_EQ(writer.index().scenes.size(), 3u);
  EXPECT_TRUE(writer.isComplete("plain/single/cocacola/06"));
  EXPECT_EQ(Database::open(dir_.path()).list().front().disparity.filename(), "disparity.png");
  // Every file the record names counts, the new ones too; an empty optional one does not.
  fs::remove(dir_.path() / "scenes/plain/single/cocacola/06/mask.png");
  EXPECT_FALSE(writer.isComplete("plain/single/cocacola/06"));
  record = writer.index().scenes.at(0);
  ASSERT_EQ(record.id, "plain/single/cocacola/06");
  record.files.mask.clear();
  writer.addScene(record);
  EXPECT_TRUE(writer.isComplete("plain/single/cocacola/06"));
  EXPECT_EQ(Database::open(dir_.path()).scene("plain/single/cocacola/06").mask, fs::path());
  fs::remove(dir_.path() / "scenes/plain/single/cocacola/06/cloud.ply");
  EXPECT_FALSE(writer.isComplete("plain/single/cocacola/06"));
  record.files.pointCloud = "scenes/plain/single/cocacola/06/missing.ply";
  EXPECT_THROW(writer.addScene(record), std::runtime_error);
  // Another seed cannot resume this folder.
  EXPECT_THROW(DatabaseWriter(dir_.path(), 43), std::runtime_error);
  // Nor can another camera profile once the index names one: one database, one profile.
  {
    DatabaseWriter named(dir_.path(), 42, "test", ObjectCatalog::benchmark(), "realistic");
    EXPECT_EQ(named.index().camera, "realistic");
    addFakeScene(named, SceneConditions::single(Texture::kPlain, 5, 7), 3);
  }
  EXPECT_EQ(readIndex(dir_.path() / "index.xml").camera, "realistic");
  try {
    DatabaseWriter(dir_.path(), 42, "test", ObjectCatalog::benchmark(), "ideal");
    ADD_FAILURE() << "a resume with another camera profile was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("camera profile \"realistic\", not \"ideal\""),
              std::string::npos)
        << e.what();
  }
  // An invalid record is refused.
  record.id = "plain/single/cocacola/05";
  EXPECT_THROW(writer.addScene(record), std::invalid_argument);
}

}  // namespace
}  // namespace visgrab::database
