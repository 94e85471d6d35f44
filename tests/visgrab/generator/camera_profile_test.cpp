// Camera profiles: the shipped ones (ideal = the rig as it always was; realistic within the
// ranges of real industrial stereo heads), profile lookup by name, and bad files reported with
// their file and line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "rw/common/diagnostic.hpp"
#include "support/test_support.hpp"
#include "visgrab/generator/camera_profile.hpp"
#include "visgrab/objects/object_model.hpp"

namespace {

namespace gen = visgrab::generator;

std::filesystem::path camerasDir() { return visgrab::test::sourceDir() / "scenes/cameras"; }

// The message of the LoadError that loading `xml` (as "bad.xml") throws, or "" if none.
std::string loadError(const std::string& xml) {
  try {
    gen::loadCameraProfileFromString(xml, "bad.xml");
  } catch (const rw::common::LoadError& e) {
    return e.what();
  }
  return {};
}

TEST(CameraProfile, TheShippedIdealProfileIsTheDefaultRig) {
  const gen::CameraProfile ideal = gen::loadCameraProfile(camerasDir() / "ideal.xml");
  const gen::CameraProfile defaults;
  EXPECT_EQ(ideal.name, "ideal");
  EXPECT_EQ(ideal.rig.width, 720);
  EXPECT_EQ(ideal.rig.height, 540);
  EXPECT_EQ(ideal.rig.focal, 810.0);
  EXPECT_EQ(ideal.rig.baseline, 0.12);
  EXPECT_EQ(ideal.rig.eye, defaults.rig.eye);
  EXPECT_EQ(ideal.rig.target, defaults.rig.target);
  EXPECT_EQ(ideal.rig.noiseSigma, 1.2);
  EXPECT_EQ(ideal.rig.blurSigma, 0.5);
  EXPECT_TRUE(ideal.alreadyRectified());
  EXPECT_EQ(ideal.vignetting, 0.0);
  EXPECT_EQ(ideal.shotNoise, 0.0);
  EXPECT_EQ(ideal.bayer, gen::BayerPattern::kNone);
  EXPECT_TRUE(ideal.materials.empty());
  EXPECT_TRUE(ideal.lights.empty());
  for (const auto& c : ideal.cameras) {
    EXPECT_EQ(c.exposure, 1.0);
    EXPECT_EQ(c.gain, 1.0);
  }
}

TEST(CameraProfile, TheRealisticProfileIsWithinTheRangesOfRealStereoHeads) {
  const gen::CameraProfile p = gen::loadCameraProfile(camerasDir() / "realistic.xml");
  EXPECT_EQ(p.name, "realistic");
  EXPECT_FALSE(p.alreadyRectified());
  for (const auto& c : p.cameras) {
    EXPECT_LE(c.distortion[0], -0.1);
    EXPECT_GE(c.distortion[0], -0.3);
  }
  for (const double a : p.misalignmentRpy) EXPECT_LT(std::abs(a), 1.0);
  const double exposureLeft = p.cameras[0].exposure * p.cameras[0].gain;
  const double exposureRight = p.cameras[1].exposure * p.cameras[1].gain;
  const double difference = std::abs(exposureLeft - exposureRight) / exposureLeft;
  EXPECT_GE(difference, 0.05);
  EXPECT_LE(difference, 0.15);
  EXPECT_GE(p.vignetting, 0.2);
  EXPECT_LE(p.vignetting, 0.4);
  EXPECT_EQ(p.bayer, gen::BayerPattern::kRggb);
  EXPECT_EQ(p.materials.size(), 3u);
}

TEST(CameraProfile, FoundByNameOrFileAndAnUnknownNameListsTheKnownOnes) {
  EXPECT_EQ(gen::findCameraProfile("realistic", camerasDir()).name, "realistic");
  EXPECT_EQ(gen::findCameraProfile((camerasDir() / "ideal.xml").string(), "/nowhere").name,
            "ideal");
  EXPECT_EQ(gen::knownCameraProfiles(camerasDir()),
            (std::vector<std::string>{"ideal", "realistic"}));
  try {
    gen::findCameraProfile("realstic", camerasDir());
    FAIL() << "an unknown profile must be refused";
  } catch (const std::invalid_argument& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("unknown camera profile \"realstic\""), std::string::npos) << what;
    EXPECT_NE(what.find("known profiles: ideal, realistic"), std::string::npos) << what;
  }
}

TEST(CameraProfile, BadValuesAreReportedWithFileAndLine) {
  const std::string head = "<CameraProfile name=\"x\">\n";
  // A value out of range: the loader's own check.
  std::string e =
      loadError(head + "  <Camera side=\"left\"\n   exposure=\"0\"/>\n</CameraProfile>");
  EXPECT_NE(e.find("bad.xml:2"), std::string::npos) << e;
  EXPECT_NE(e.find("attribute exposure must be in (0, 10], got 0"), std::string::npos) << e;
  // Not a number: the schema, explained.
  e = loadError(head + "  <Sensor readNoise=\"loud\"/>\n</CameraProfile>");
  EXPECT_NE(e.find("bad.xml:2"), std::string::npos) << e;
  EXPECT_NE(e.find("readNoise"), std::string::npos) << e;
  // Four distortion coefficients instead of five.
  e = loadError(head +
                "\n  <Camera side=\"right\" distortion=\"-0.2 0.1 0 0\"/>\n</CameraProfile>");
  EXPECT_NE(e.find("bad.xml:3"), std::string::npos) << e;
  EXPECT_NE(e.find("distortion"), std::string::npos) << e;
  // A misalignment of 10 degrees.
  e = loadError(head + "  <Rig misalignmentRpy=\"10 0 0\"/>\n</CameraProfile>");
  EXPECT_NE(e.find("bad.xml:2"), std::string::npos) << e;
  EXPECT_NE(e.find("within +-5 degrees, got 10"), std::string::npos) << e;
  // A material given twice.
  e = loadError(head +
                "  <Material name=\"metal\" specular=\"1\" shininess=\"50\"/>\n"
                "  <Material name=\"metal\" specular=\"1\" shininess=\"60\"/>\n</CameraProfile>");
  EXPECT_NE(e.find("bad.xml:3"), std::string::npos) << e;
  EXPECT_NE(e.find("material \"metal\" is given twice"), std::string::npos) << e;
  // An unknown mosaic and an unknown element.
  e = loadError(head + "  <Sensor bayer=\"GRBG\"/>\n</CameraProfile>");
  EXPECT_NE(e.find("bad.xml:2"), std::string::npos) << e;
  e = loadError(head + "  <Lens k1=\"0\"/>\n</CameraProfile>");
  EXPECT_NE(e.find("bad.xml:2"), std::string::npos) << e;
  EXPECT_NE(e.find("Lens"), std::string::npos) << e;
  // A missing file.
  try {
    gen::loadCameraProfile("/nowhere/profile.xml");
    FAIL();
  } catch (const rw::common::LoadError& error) {
    EXPECT_NE(std::string(error.what()).find("/nowhere/profile.xml"), std::string::npos);
  }
}

// Schema errors say what is wrong (issue 20): out of order, misspelt.
TEST(CameraProfile, SchemaErrorsSayWhatIsWrong) {
  const std::string head = "<CameraProfile name=\"x\">\n";
  std::string e = loadError(head +
                            "  <Sensor readNoise=\"1\"/>\n  <Rig baseline=\"0.1\"/>\n"
                            "</CameraProfile>");
  EXPECT_NE(e.find("bad.xml:3:3: error: <Rig> is out of order: it must come before <Sensor>"),
            std::string::npos)
      << e;
  e = loadError(head + "  <Sensr readNoise=\"1\"/>\n</CameraProfile>");
  EXPECT_NE(e.find("bad.xml:2:3: error: unknown element <Sensr> in <CameraProfile "
                   "name=\"x\">; did you mean <Sensor>?"),
            std::string::npos)
      << e;
}

TEST(CameraProfile, OmittedValuesKeepTheIdealOnes) {
  const gen::CameraProfile p = gen::loadCameraProfileFromString(
      "<CameraProfile name=\"mosaic\"><Sensor bayer=\"RGGB\"/></CameraProfile>", "m.xml");
  EXPECT_EQ(p.name, "mosaic");
  EXPECT_EQ(p.bayer, gen::BayerPattern::kRggb);
  EXPECT_EQ(p.rig.noiseSigma, 1.2);
  EXPECT_TRUE(p.alreadyRectified());
}

// The finishes apply to the parts the object models mark with a material: a can's body and
// lids are metal, a jar's body glass with a metal lid, a printed box has none.
TEST(CameraProfile, ObjectPartsCarryTheMaterialsProfilesGiveAFinish) {
  namespace obj = visgrab::objects;
  const auto spec = obj::loadObjectSpecs(visgrab::test::sourceDir() / "scenes/objects/objects.xml");
  const auto materials = [&](const char* name) {
    std::vector<std::optional<obj::SurfaceMaterial>> out;
    for (const auto& part : obj::generateObject(*spec.findObject(name)).visual) {
      out.push_back(part.material);
    }
    return out;
  };
  for (const auto& m : materials("cocacola")) EXPECT_EQ(m, obj::SurfaceMaterial::kMetal);
  const auto jar = materials("marmelade");
  EXPECT_NE(std::find(jar.begin(), jar.end(), obj::SurfaceMaterial::kGlass), jar.end());
  EXPECT_NE(std::find(jar.begin(), jar.end(), obj::SurfaceMaterial::kMetal), jar.end());
  for (const auto& m : materials("amicelli")) EXPECT_FALSE(m.has_value());
}

}  // namespace
