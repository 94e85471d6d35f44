// The noise model of robust verdicts (docs/noise-model.md): its defaults and example files, the
// XML format and every error of it at its line, and the seeded perturbations checked against
// their definition (draw order, Rodrigues' formula) and against their statistics.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <numbers>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "rw/common/diagnostic.hpp"
#include "rw/common/text_file.hpp"
#include "support/test_support.hpp"
#include "visgrab/results/statistics.hpp"
#include "visgrab/runner/noise_model.hpp"

namespace {

namespace runner = visgrab::runner;
using runner::NoiseModel;
using runner::Perturbation;

constexpr double kDegree = std::numbers::pi / 180.0;

std::filesystem::path noiseDir() { return visgrab::test::sourceDir() / "scenes/noise"; }

// A model whose every sigma is zero.
NoiseModel silentModel() { return NoiseModel{0.0, 0.0, 0.0, 0.0, 0.0, 0.0}; }

// The LoadError that parsing `xml` as "bad.xml" throws; fails the test if there is none.
rw::common::LoadError loadError(const std::string& xml) {
  try {
    runner::parseNoiseModel(xml, "bad.xml");
  } catch (const rw::common::LoadError& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << xml;
  return rw::common::LoadError({});
}

// The numbers in `text` (tokens separated by blanks and ';' that read as a whole number).
std::vector<double> numbersIn(const std::string& text) {
  std::vector<double> out;
  std::string token;
  const auto flush = [&] {
    double v = 0.0;
    const auto r = std::from_chars(token.data(), token.data() + token.size(), v);
    if (!token.empty() && r.ec == std::errc() && r.ptr == token.data() + token.size()) {
      out.push_back(v);
    }
    token.clear();
  };
  for (const char c : text) {
    if (c == ' ' || c == ';') {
      flush();
    } else {
      token += c;
    }
  }
  flush();
  return out;
}

// The rotation vector (angle times axis) of a rotation matrix.
Eigen::Vector3d rotationVectorOf(const rw::math::Rotation3D& R) {
  const Eigen::AngleAxisd aa(R);
  return aa.angle() * aa.axis();
}

// exp([w]x) by Rodrigues' formula, written out: I + sin(t) K + (1 - cos(t)) K^2, t = |w|,
// K the cross-product matrix of w / t.
rw::math::Rotation3D rodrigues(const Eigen::Vector3d& w) {
  const double t = w.norm();
  if (t == 0.0) return rw::math::Rotation3D::Identity();
  const Eigen::Vector3d k = w / t;
  rw::math::Rotation3D K;
  K << 0.0, -k.z(), k.y(), k.z(), 0.0, -k.x(), -k.y(), k.x(), 0.0;
  return rw::math::Rotation3D::Identity() + std::sin(t) * K + (1.0 - std::cos(t)) * K * K;
}

// Sample mean and standard deviation.
struct Moments {
  double mean = 0.0;
  double std = 0.0;
};

Moments momentsOf(const std::vector<double>& x) {
  Moments m;
  for (const double v : x) m.mean += v;
  m.mean /= static_cast<double>(x.size());
  double ss = 0.0;
  for (const double v : x) ss += (v - m.mean) * (v - m.mean);
  m.std = std::sqrt(ss / static_cast<double>(x.size() - 1));
  return m;
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const Moments ma = momentsOf(a);
  const Moments mb = momentsOf(b);
  double s = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) s += (a[i] - ma.mean) * (b[i] - mb.mean);
  return s / static_cast<double>(a.size() - 1) / (ma.std * mb.std);
}

// ---------------------------------------------------------------------------------------------
// Defaults and example files

TEST(NoiseModel, DefaultsAreTheDocumentedOnes) {
  const NoiseModel d = runner::defaultNoiseModel();
  EXPECT_EQ(d.handTranslation, 0.002);
  EXPECT_EQ(d.handRotation, std::numbers::pi / 180.0);
  EXPECT_EQ(d.objectTranslation, 0.002);
  EXPECT_EQ(d.objectRotation, std::numbers::pi / 180.0);
  EXPECT_EQ(d.friction, 0.1);
  EXPECT_EQ(d.mass, 0.1);
  EXPECT_EQ(d, NoiseModel{});
  EXPECT_NO_THROW(runner::checkNoiseModel(d));
}

TEST(NoiseModel, TheDefaultFileHoldsTheDefaults) {
  EXPECT_EQ(runner::loadNoiseModel(noiseDir() / "default.noise.xml"), runner::defaultNoiseModel());
}

TEST(NoiseModel, ThePoseOnlyExampleKeepsTheDefaultPosesAndSwitchesThePhysicsOff) {
  NoiseModel expected = runner::defaultNoiseModel();
  expected.friction = 0.0;
  expected.mass = 0.0;
  EXPECT_EQ(runner::loadNoiseModel(noiseDir() / "pose-only.noise.xml"), expected);
}

TEST(NoiseModel, EveryExampleFileReads) {
  std::set<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(noiseDir())) {
    names.insert(entry.path().filename().string());
    EXPECT_NO_THROW(runner::loadNoiseModel(entry.path())) << entry.path();
  }
  EXPECT_EQ(names, (std::set<std::string>{"default.noise.xml", "pose-only.noise.xml"}));
}

TEST(NoiseModel, TheDocumentedExampleReads) {
  std::string doc;
  ASSERT_TRUE(
      rw::common::readTextFile(visgrab::test::sourceDir() / "docs/noise-model.md", doc).empty());
  const std::string start = "### Example\n\n```xml\n";
  const auto from = doc.find(start);
  ASSERT_NE(from, std::string::npos);
  const auto to = doc.find("```", from + start.size());
  const NoiseModel m = runner::parseNoiseModel(
      doc.substr(from + start.size(), to - from - start.size()), "noise-model.md");
  EXPECT_EQ(m.handTranslation, 0.005);
  EXPECT_EQ(m.handRotation, 0.0);
  EXPECT_EQ(m.objectTranslation, 0.002);  // left out: the default
  EXPECT_EQ(m.objectRotation, kDegree);
  EXPECT_EQ(m.friction, 0.2);
  EXPECT_EQ(m.mass, 0.0);
}

// The loader validates against the schema compiled in at build time: the published file.
TEST(NoiseModel, SchemaIsTheFileInTheXmlFolder) {
  std::string xsd;
  ASSERT_TRUE(
      rw::common::readTextFile(visgrab::test::sourceDir() / "xml/noise-model.xsd", xsd).empty());
  EXPECT_EQ(runner::noiseModelSchema(), xsd);
}

// ---------------------------------------------------------------------------------------------
// The format

TEST(NoiseModel, LeftOutPartsKeepTheirDefaultsAndAZeroSigmaSwitchesAPartOff) {
  EXPECT_EQ(runner::parseNoiseModel("<NoiseModel/>", "empty.xml"), runner::defaultNoiseModel());
  const NoiseModel m = runner::parseNoiseModel(
      "<?xml version=\"1.0\"?>\n<NoiseModel>\n  <Hand translation=\"0\" rotation=\"0\"/>\n"
      "  <Mass sigma=\" 0.25 \"/>\n</NoiseModel>\n",
      "some.xml");
  NoiseModel expected = runner::defaultNoiseModel();
  expected.handTranslation = 0.0;
  expected.handRotation = 0.0;
  expected.mass = 0.25;
  EXPECT_EQ(m, expected);
  // "-0" is a zero, and describe() shows it as one.
  const NoiseModel z =
      runner::parseNoiseModel("<NoiseModel><Friction sigma=\"-0\"/></NoiseModel>", "zero.xml");
  EXPECT_FALSE(std::signbit(z.friction));
  // The bounds themselves are allowed.
  const NoiseModel wide = runner::parseNoiseModel(
      "<NoiseModel><Hand translation=\"0.05\" rotation=\"0.7853981633974483\"/>"
      "<Friction sigma=\"0.5\"/></NoiseModel>",
      "wide.xml");
  EXPECT_EQ(wide.handTranslation, runner::kMaxTranslationSigma);
  EXPECT_EQ(wide.handRotation, runner::kMaxRotationSigma);
  EXPECT_EQ(wide.friction, runner::kMaxRelativeSigma);
}

struct BadFile {
  const char* name;
  const char* xml;
  int line;
  int column;
  const char* message;
};

class NoiseModelBadFileTest : public ::testing::TestWithParam<BadFile> {};

TEST_P(NoiseModelBadFileTest, IsOneErrorAtItsLine) {
  const BadFile& bad = GetParam();
  const rw::common::LoadError e = loadError(bad.xml);
  ASSERT_EQ(e.diagnostics().size(), 1u) << e.what();
  const rw::common::Diagnostic& d = e.diagnostics()[0];
  EXPECT_EQ(d.severity, rw::common::Diagnostic::Severity::kError);
  EXPECT_EQ(d.file, "bad.xml");
  EXPECT_EQ(d.line, bad.line) << e.what();
  EXPECT_EQ(d.column, bad.column) << e.what();
  EXPECT_EQ(d.message, bad.message);
  const std::string where =
      "bad.xml:" + std::to_string(bad.line) + ":" + std::to_string(bad.column) + ": error: ";
  EXPECT_EQ(std::string(e.what()), where + bad.message);
}

INSTANTIATE_TEST_SUITE_P(
    Files, NoiseModelBadFileTest,
    ::testing::Values(
        BadFile{"NotWellFormed", "<NoiseModel>\n  <Friction sigma=\"0.1\"/>\n</NoiseModl>", 3, 3,
                "not well-formed XML: expected end of tag 'NoiseModel' (opened at line 1)"},
        BadFile{"Unterminated", "<NoiseModel>\n  <Friction sigma=\"0.1\"/>\n", 2, 26,
                "not well-formed XML: expected end of tag 'NoiseModel' (opened at line 1)"},
        // An unclosed part: the missing end tag is the error, not the text the part then seems
        // to hold.
        BadFile{"UnclosedPart",
                "<NoiseModel>\n  <Hand translation=\"0.002\" rotation=\"0.01\">\n</NoiseModel>", 3,
                3, "not well-formed XML: expected end of tag 'Hand' (opened at line 2)"},
        BadFile{"OtherRoot", "<CameraProfile name=\"x\"/>", 1, 1,
                "unknown element <CameraProfile>"},
        BadFile{"MisspeltRoot", "<!-- a model -->\n<NoiseModle/>", 2, 1,
                "unknown element <NoiseModle>; did you mean <NoiseModel>?"},
        BadFile{"PartAsRoot", "<Hand translation=\"0\" rotation=\"0\"/>", 1, 1,
                "<Hand> is not allowed here"},
        BadFile{"NoRoot", "<!-- nothing -->\n", 1, 1,
                "expected a <NoiseModel> element, found none"},
        BadFile{"EmptyFile", "", 1, 1, "expected a <NoiseModel> element, found none"},
        BadFile{"TwoRoots", "<NoiseModel/>\n\n<NoiseModel/>", 3, 1,
                "a second <NoiseModel> element; a file holds one (the first is at line 1)"},
        BadFile{"UnknownElement",
                "<NoiseModel>\n  <Hnd translation=\"0\" rotation=\"0\"/>\n"
                "</NoiseModel>",
                2, 3, "unknown element <Hnd> in <NoiseModel>; did you mean <Hand>?"},
        BadFile{"ElementInAPart",
                "<NoiseModel>\n  <Hand translation=\"0\" rotation=\"0\">"
                "<Mass sigma=\"0\"/></Hand>\n</NoiseModel>",
                2, 38, "<Mass> is not allowed in <Hand> (expected <EMPTY> here)"},
        BadFile{"UnknownAttribute",
                "<NoiseModel>\n  <Hand translation=\"0\" rotation=\"0\" "
                "scale=\"1\"/>\n</NoiseModel>",
                2, 3, "<Hand>: unknown attribute \"scale\""},
        BadFile{"UnknownRootAttribute", "<NoiseModel version=\"1\"/>", 1, 1,
                "<NoiseModel>: unknown attribute \"version\""},
        BadFile{"MissingAttribute", "<NoiseModel>\n  <Object translation=\"0\"/>\n</NoiseModel>", 2,
                3, "<Object>: missing required attribute \"rotation\""},
        BadFile{"RepeatedElement",
                "<NoiseModel>\n  <Mass sigma=\"0.1\"/>\n  <Mass sigma=\"0.2\"/>\n"
                "</NoiseModel>",
                3, 3,
                "<Mass> is given twice; <NoiseModel> allows only one (the first is at line 2)"},
        BadFile{"OutOfOrder",
                "<NoiseModel>\n  <Mass sigma=\"0.1\"/>\n  <Hand translation=\"0\" "
                "rotation=\"0\"/>\n</NoiseModel>",
                3, 3, "<Hand> is out of order: it must come before <Mass>"},
        BadFile{"TextInAPart", "<NoiseModel>\n  <Mass sigma=\"0.1\">x</Mass>\n</NoiseModel>", 2, 3,
                "<Mass>: text is not allowed here (\"x\")"},
        BadFile{"TextInTheRoot", "<NoiseModel>\n  oops\n</NoiseModel>", 1, 1,
                "<NoiseModel>: text is not allowed here (\"oops\")"},
        BadFile{"TextOutside", "text <NoiseModel/>", 1, 6,
                "text outside of the elements (\"text\")"},
        BadFile{"NotANumber", "<NoiseModel>\n  <Mass sigma=\"abc\"/>\n</NoiseModel>", 2, 3,
                "<Mass>: attribute sigma: \"abc\" is not a number"},
        BadFile{"HexNumber", "<NoiseModel>\n  <Mass sigma=\"0x1p-3\"/>\n</NoiseModel>", 2, 3,
                "<Mass>: attribute sigma: \"0x1p-3\" is not a number"},
        BadFile{"EmptyValue", "<NoiseModel>\n  <Friction sigma=\"\"/>\n</NoiseModel>", 2, 3,
                "<Friction>: attribute sigma: a number is missing"},
        BadFile{"NaN", "<NoiseModel>\n  <Friction sigma=\"NaN\"/>\n</NoiseModel>", 2, 3,
                "<Friction>: attribute sigma: \"NaN\" is not a finite number"},
        BadFile{"Infinite",
                "<NoiseModel>\n  <Hand translation=\"INF\" rotation=\"0\"/>\n"
                "</NoiseModel>",
                2, 3, "<Hand>: attribute translation: \"INF\" is not a finite number"},
        BadFile{"Overflow",
                "<NoiseModel>\n  <Hand translation=\"0\" rotation=\"1e400\"/>\n"
                "</NoiseModel>",
                2, 3, "<Hand>: attribute rotation: \"1e400\" is out of range"},
        BadFile{"NegativeRelative", "<NoiseModel>\n  <Mass sigma=\"-0.1\"/>\n</NoiseModel>", 2, 3,
                "<Mass>: attribute sigma: expected a relative sigma from 0 to 0.5, got -0.1"},
        BadFile{"NegativeTranslation",
                "<NoiseModel>\n  <Object translation=\"-0.001\" "
                "rotation=\"0\"/>\n</NoiseModel>",
                2, 3,
                "<Object>: attribute translation: expected a sigma from 0 to 0.05 m, got -0.001"},
        BadFile{"NegativeRotation",
                "<NoiseModel>\n  <Object translation=\"0\" "
                "rotation=\"-1e-9\"/>\n</NoiseModel>",
                2, 3,
                "<Object>: attribute rotation: expected a sigma from 0 to 0.7853981633974483 rad "
                "(pi/4), got -1e-09"},
        BadFile{"RelativeSigmaOfOne", "<NoiseModel>\n  <Mass sigma=\"1\"/>\n</NoiseModel>", 2, 3,
                "<Mass>: attribute sigma: expected a relative sigma from 0 to 0.5, got 1 (a "
                "fraction of the value it scales: 10 % is 0.1)"},
        BadFile{"RelativeSigmaOnTheNextLine",
                "<NoiseModel>\n  <Friction\n     sigma=\"0.9\"/>\n"
                "</NoiseModel>",
                2, 3,
                "<Friction>: attribute sigma: expected a relative sigma from 0 to 0.5, got 0.9 (a "
                "fraction of the value it scales: 10 % is 0.1)"},
        BadFile{"DegreesForRadians",
                "<NoiseModel>\n  <Hand translation=\"0\" rotation=\"1\"/>\n"
                "</NoiseModel>",
                2, 3,
                "<Hand>: attribute rotation: expected a sigma from 0 to 0.7853981633974483 rad "
                "(pi/4), got 1 (angles are in radians: 1 degree is 0.017453292519943295)"},
        BadFile{"MillimetresForMetres",
                "<NoiseModel>\n  <Object translation=\"2\" "
                "rotation=\"0\"/>\n</NoiseModel>",
                2, 3,
                "<Object>: attribute translation: expected a sigma from 0 to 0.05 m, got 2 "
                "(lengths are in metres: 2 mm is 0.002)"}),
    [](const ::testing::TestParamInfo<BadFile>& p) { return std::string(p.param.name); });

TEST(NoiseModel, EveryBadValueOfAFileIsReported) {
  const rw::common::LoadError e =
      loadError("<NoiseModel>\n  <Friction sigma=\"2\"/>\n  <Mass sigma=\"-1\"/>\n</NoiseModel>");
  ASSERT_EQ(e.diagnostics().size(), 2u) << e.what();
  EXPECT_EQ(e.diagnostics()[0].line, 2);
  EXPECT_EQ(e.diagnostics()[1].line, 3);
  EXPECT_NE(std::string(e.what()).find("bad.xml:3:3: error: <Mass>: attribute sigma: expected a "
                                       "relative sigma from 0 to 0.5, got -1"),
            std::string::npos)
      << e.what();
}

TEST(NoiseModel, AnUnreadableFileIsNamed) {
  try {
    runner::loadNoiseModel("/nowhere/x.noise.xml");
    FAIL() << "a missing file must be refused";
  } catch (const rw::common::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("cannot read /nowhere/x.noise.xml"), std::string::npos)
        << e.what();
  }
  try {
    runner::loadNoiseModel(noiseDir());
    FAIL() << "a folder must be refused";
  } catch (const rw::common::LoadError& e) {
    EXPECT_NE(std::string(e.what()).find("scenes/noise"), std::string::npos) << e.what();
  }
}

TEST(NoiseModel, DescribeIsExactAndTellsModelsApart) {
  EXPECT_EQ(runner::describe(runner::defaultNoiseModel()),
            "hand 0.002 m 0.017453292519943295 rad; object 0.002 m 0.017453292519943295 rad; "
            "friction 0.1; mass 0.1");
  EXPECT_EQ(runner::describe(silentModel()),
            "hand 0 m 0 rad; object 0 m 0 rad; friction 0; mass 0");
  const NoiseModel m{0.001234, 0.0123456789, 0.0031, 1e-7, 0.123456789012345, 0.3};
  EXPECT_EQ(numbersIn(runner::describe(m)),
            (std::vector<double>{m.handTranslation, m.handRotation, m.objectTranslation,
                                 m.objectRotation, m.friction, m.mass}));
  // Each field moved by one unit in the last place gives another line.
  const std::array<double NoiseModel::*, 6> fields{
      &NoiseModel::handTranslation, &NoiseModel::handRotation, &NoiseModel::objectTranslation,
      &NoiseModel::objectRotation,  &NoiseModel::friction,     &NoiseModel::mass};
  std::set<std::string> lines{runner::describe(m)};
  for (const auto field : fields) {
    NoiseModel other = m;
    other.*field = std::nextafter(other.*field, 1.0);
    lines.insert(runner::describe(other));
  }
  EXPECT_EQ(lines.size(), 7u);
}

// ---------------------------------------------------------------------------------------------
// Sampling

TEST(NoiseModel, ZeroSigmasGiveTheIdentityExactly) {
  for (const std::uint64_t seed : {0ULL, 1ULL, 42ULL, 0xFFFFFFFFFFFFFFFFULL}) {
    const Perturbation p = runner::samplePerturbation(silentModel(), seed);
    EXPECT_TRUE(p.X_tcp_perturbed.matrix() == Eigen::Matrix4d::Identity()) << seed;
    EXPECT_EQ(p.objectDx, 0.0);
    EXPECT_EQ(p.objectDy, 0.0);
    EXPECT_EQ(p.objectYaw, 0.0);
    EXPECT_FALSE(std::signbit(p.objectDx) || std::signbit(p.objectDy) || std::signbit(p.objectYaw));
    EXPECT_EQ(p.frictionScale, 1.0);
    EXPECT_EQ(p.massScale, 1.0);
  }
  const Perturbation identity;
  EXPECT_TRUE(identity.X_tcp_perturbed.matrix() == Eigen::Matrix4d::Identity());
  EXPECT_EQ(identity.frictionScale, 1.0);
  EXPECT_EQ(identity.massScale, 1.0);
}

// Repeats' perturbations are pinned to the documented order of draws: draw the 11 normals
// here and build what each part must be from its definition.
TEST(NoiseModel, DrawsFollowTheDocumentedOrder) {
  const NoiseModel m{0.003, 0.05, 0.004, 0.03, 0.15, 0.2};
  for (const std::uint64_t seed : {7ULL, 20120601ULL, 0xDEADBEEFULL}) {
    visgrab::results::SeededRandom random(seed);
    std::array<double, 11> z{};
    for (double& v : z) v = random.normal();
    const Perturbation p = runner::samplePerturbation(m, seed);
    const Eigen::Vector3d t = m.handTranslation * Eigen::Vector3d(z[0], z[1], z[2]);
    const Eigen::Vector3d w = m.handRotation * Eigen::Vector3d(z[3], z[4], z[5]);
    EXPECT_EQ(p.X_tcp_perturbed.translation(), t);
    EXPECT_LT((p.X_tcp_perturbed.linear() - rodrigues(w)).cwiseAbs().maxCoeff(), 1e-15);
    EXPECT_TRUE(p.X_tcp_perturbed.matrix().row(3) == Eigen::RowVector4d(0, 0, 0, 1));
    EXPECT_EQ(p.objectDx, m.objectTranslation * z[6]);
    EXPECT_EQ(p.objectDy, m.objectTranslation * z[7]);
    EXPECT_EQ(p.objectYaw, m.objectRotation * z[8]);
    EXPECT_EQ(p.frictionScale, 1.0 + m.friction * z[9]);
    EXPECT_EQ(p.massScale, 1.0 + m.mass * z[10]);
  }
}

TEST(NoiseModel, APartsDrawsDoNotDependOnTheOtherParts) {
  const NoiseModel all = runner::defaultNoiseModel();
  NoiseModel frictionOnly = silentModel();
  frictionOnly.friction = all.friction;
  NoiseModel handOnly = silentModel();
  handOnly.handTranslation = all.handTranslation;
  handOnly.handRotation = all.handRotation;
  for (std::uint64_t seed = 1; seed <= 20; ++seed) {
    const Perturbation p = runner::samplePerturbation(all, seed);
    EXPECT_EQ(runner::samplePerturbation(frictionOnly, seed).frictionScale, p.frictionScale);
    EXPECT_TRUE(runner::samplePerturbation(handOnly, seed).X_tcp_perturbed.matrix() ==
                p.X_tcp_perturbed.matrix());
  }
}

TEST(NoiseModel, SamplingIsDeterministicAndSeedsDiffer) {
  const NoiseModel m = runner::defaultNoiseModel();
  const Perturbation a = runner::samplePerturbation(m, 12345);
  const Perturbation b = runner::samplePerturbation(m, 12345);
  EXPECT_TRUE(a.X_tcp_perturbed.matrix() == b.X_tcp_perturbed.matrix());
  EXPECT_EQ(a.objectDx, b.objectDx);
  EXPECT_EQ(a.objectDy, b.objectDy);
  EXPECT_EQ(a.objectYaw, b.objectYaw);
  EXPECT_EQ(a.frictionScale, b.frictionScale);
  EXPECT_EQ(a.massScale, b.massScale);
  std::set<double> xs;
  std::set<double> masses;
  for (std::uint64_t seed = 0; seed < 200; ++seed) {
    const Perturbation p = runner::samplePerturbation(m, seed);
    xs.insert(p.X_tcp_perturbed.translation().x());
    masses.insert(p.massScale);
  }
  EXPECT_EQ(xs.size(), 200u);
  EXPECT_EQ(masses.size(), 200u);
}

// Over 20,000 seeds every component is a zero-mean Gaussian with its sigma, and the components
// are uncorrelated. Bounds: the mean within 4 standard errors (sigma / sqrt(n)), the sample
// standard deviation within 3 % (about 6 of its standard errors, sigma / sqrt(2 n)), correlations
// below 0.04 (about 6 of theirs, 1 / sqrt(n)); a sigma off by 5 % fails.
TEST(NoiseModel, SampleStatisticsMatchTheSigmas) {
  const NoiseModel m{0.003, 0.05, 0.004, 0.03, 0.15, 0.2};
  constexpr int kSamples = 20000;
  std::array<std::vector<double>, 11> c;
  for (int i = 0; i < kSamples; ++i) {
    const Perturbation p = runner::samplePerturbation(
        m, visgrab::results::deriveSeed(99, static_cast<std::uint64_t>(i)));
    const Eigen::Vector3d t = p.X_tcp_perturbed.translation();
    const Eigen::Vector3d w = rotationVectorOf(p.X_tcp_perturbed.linear());
    const std::array<double, 11> v{t.x(),
                                   t.y(),
                                   t.z(),
                                   w.x(),
                                   w.y(),
                                   w.z(),
                                   p.objectDx,
                                   p.objectDy,
                                   p.objectYaw,
                                   p.frictionScale - 1.0,
                                   p.massScale - 1.0};
    for (std::size_t k = 0; k < v.size(); ++k) c[k].push_back(v[k]);
  }
  const std::array<double, 11> sigma{m.handTranslation,
                                     m.handTranslation,
                                     m.handTranslation,
                                     m.handRotation,
                                     m.handRotation,
                                     m.handRotation,
                                     m.objectTranslation,
                                     m.objectTranslation,
                                     m.objectRotation,
                                     m.friction,
                                     m.mass};
  for (std::size_t k = 0; k < c.size(); ++k) {
    const Moments mo = momentsOf(c[k]);
    EXPECT_LT(std::abs(mo.mean), 4.0 * sigma[k] / std::sqrt(kSamples)) << "component " << k;
    EXPECT_NEAR(mo.std / sigma[k], 1.0, 0.03) << "component " << k;
    for (std::size_t l = k + 1; l < c.size(); ++l) {
      EXPECT_LT(std::abs(correlation(c[k], c[l])), 0.04) << "components " << k << ", " << l;
    }
  }
}

// At the largest relative sigma, 0.5, a factor 1 + 0.5 z falls below the floor 0.05 when
// z < -1.9: Phi(-1.9) = 2.872 % of the draws, which must sit on the floor exactly.
TEST(NoiseModel, TheFloorHolds) {
  NoiseModel m = silentModel();
  m.friction = runner::kMaxRelativeSigma;
  m.mass = runner::kMaxRelativeSigma;
  constexpr int kSamples = 20000;
  int frictionFloored = 0;
  int massFloored = 0;
  double smallest = 1.0;
  for (int i = 0; i < kSamples; ++i) {
    const Perturbation p = runner::samplePerturbation(m, static_cast<std::uint64_t>(i));
    ASSERT_GE(p.frictionScale, runner::kNoiseScaleFloor);
    ASSERT_GE(p.massScale, runner::kNoiseScaleFloor);
    if (p.frictionScale == runner::kNoiseScaleFloor) ++frictionFloored;
    if (p.massScale == runner::kNoiseScaleFloor) ++massFloored;
    smallest = std::min({smallest, p.frictionScale, p.massScale});
  }
  EXPECT_EQ(runner::kNoiseScaleFloor, 0.05);
  EXPECT_EQ(smallest, runner::kNoiseScaleFloor);
  const double expected = 0.5 * std::erfc(1.9 / std::numbers::sqrt2);
  EXPECT_NEAR(expected, 0.02872, 1e-5);
  // Within 4 standard errors, sqrt(p (1 - p) / n) = 0.118 %.
  EXPECT_NEAR(static_cast<double>(frictionFloored) / kSamples, expected, 0.0048);
  EXPECT_NEAR(static_cast<double>(massFloored) / kSamples, expected, 0.0048);
}

TEST(NoiseModel, RotationsAreOrthonormal) {
  NoiseModel m = silentModel();
  m.handRotation = runner::kMaxRotationSigma;
  double largest = 0.0;
  for (std::uint64_t seed = 0; seed < 2000; ++seed) {
    const rw::math::Rotation3D R = runner::samplePerturbation(m, seed).X_tcp_perturbed.linear();
    EXPECT_LT((R.transpose() * R - rw::math::Rotation3D::Identity()).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_NEAR(R.determinant(), 1.0, 1e-14);
    largest = std::max(largest, Eigen::AngleAxisd(R).angle());
  }
  EXPECT_GT(largest, 2.0);  // angles well past pi/2 are among them
}

TEST(NoiseModel, ModelsOutsideTheRulesAreRefused) {
  const auto refused = [](const std::function<void(NoiseModel&)>& change, const std::string& what) {
    NoiseModel m = runner::defaultNoiseModel();
    change(m);
    try {
      runner::samplePerturbation(m, 1);
      ADD_FAILURE() << "no error for " << what;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind("noise model: " + what, 0), 0u) << e.what();
    }
  };
  refused([](NoiseModel& m) { m.handTranslation = -0.001; }, "hand translation: expected");
  refused([](NoiseModel& m) { m.handRotation = std::nan(""); }, "hand rotation: expected");
  refused([](NoiseModel& m) { m.objectTranslation = 0.06; }, "object translation: expected");
  refused([](NoiseModel& m) { m.objectRotation = std::numeric_limits<double>::infinity(); },
          "object rotation: expected");
  refused([](NoiseModel& m) { m.friction = 0.51; }, "friction: expected");
  refused([](NoiseModel& m) { m.mass = -0.1; }, "mass: expected a relative sigma from 0 to 0.5");
}

}  // namespace
