#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string_view>
#include <vector>

#include "visgrab/database/database.hpp"
#include "visgrab/database/scene_set.hpp"
#include "visgrab/render/render_result.hpp"

/// The shared test database: 20 scenes generated with the project's objects, hand and materials
/// (scenes/), seed kTestDatabaseSeed and the default (realistic) camera profile, made once per
/// build tree and reused by every test process. Its twin with the "ideal" camera profile (the
/// same scenes and poses; clean, already rectified images) is for tests that measure an
/// algorithm's accuracy on clean images (the stereo matcher, the baseline's segmentation);
/// everything else uses the realistic one, which is what users get.
///
/// Use it for tests that need real generated scenes (images, calibration, scene files, ground
/// truth): the generator's checks against the simulator and renderer, the benchmark run, and the
/// vision tests. A test that must watch generation itself (byte equality across thread counts, an
/// interrupted and resumed run, bad inputs) generates its own small database in a TempDir.
///
/// The database lives in `<build>/tests/test-database` (docs/database-format.md describes the
/// files). The first process that asks for it generates the scenes (about 20 s on 2 cores) under
/// an exclusive lock on `<build>/tests/test-database.lock`; processes that ask meanwhile wait on
/// the lock; later ones find it complete (the generator resumes and skips finished scenes). The
/// scenes are fixed: a test may rely on their objects and, through the fixed seed, on their poses
/// (read them from the ground truth, not from constants). After changing the generator, delete
/// the folder to regenerate. Link `visgrab_test_database`.
namespace visgrab::test {

/// The scene ids of the shared test database, grouped by table and arrangement (Database::list()
/// gives them in enumerateScenes() order): both tables; on each, single objects standing (poses
/// 01-04) and lying (05-08), and pairs apart (placements 01-04) and close (05-08).
///
/// - plain: standing cocacola/01, marmelade/03, saltbox/01; lying breadbox/05, corny/07,
///   saltbox/06; apart breadbox_peachcan/03, cocacola_saltcylinder/01; close burti_denkmit/05,
///   cleaningbottle_sucker/06.
/// - textured: standing cocacola/01, greencup/02, peachcan/02, tomato/04; lying saltbox/06,
///   sucker/08; apart marmelade_pure/02, tomato_waterjug/04; close burti_denkmit/05,
///   cocacola_saltcylinder/06.
///
/// Cans, boxes, a cup with a handle, a jar, a bottle, a canister, a jug. The runner test grasps
/// the plain cocacola/01, saltbox/01, marmelade/03, cocacola_saltcylinder/01 and the textured
/// peachcan/02. Lying objects are boxes: a lying can or bottle may still roll slowly when the
/// generator calls it settled (GeneratedDatabase.SettledObjectsAreAtRestAndDoNotPenetrate).
inline constexpr std::array<std::string_view, 20> kTestSceneIds = {
    "plain/single/cocacola/01",
    "plain/single/marmelade/03",
    "plain/single/saltbox/01",
    "plain/single/breadbox/05",
    "plain/single/corny/07",
    "plain/single/saltbox/06",
    "plain/double/breadbox_peachcan/03",
    "plain/double/cocacola_saltcylinder/01",
    "plain/double/burti_denkmit/05",
    "plain/double/cleaningbottle_sucker/06",
    "textured/single/cocacola/01",
    "textured/single/greencup/02",
    "textured/single/peachcan/02",
    "textured/single/tomato/04",
    "textured/single/sucker/08",
    "textured/single/saltbox/06",
    "textured/double/marmelade_pure/02",
    "textured/double/tomato_waterjug/04",
    "textured/double/burti_denkmit/05",
    "textured/double/cocacola_saltcylinder/06",
};

/// The seed the shared test database is generated with.
inline constexpr std::uint64_t kTestDatabaseSeed = 3;

/// The conditions of kTestSceneIds, in the same order.
std::vector<database::SceneConditions> testDatabaseScenes();

/// The folder of the shared test database, generated (or completed) on the first call in a
/// process; later calls return at once. @throws std::runtime_error when a scene cannot be
/// generated or the lock cannot be taken.
const std::filesystem::path& testDatabasePath();

/// The shared test database, opened once per process (see testDatabasePath()).
const database::Database& testDatabase();

/// The ideal-camera twin (`<build>/tests/test-database-ideal`), generated on first use.
const std::filesystem::path& idealTestDatabasePath();

/// The ideal-camera twin, opened once per process.
const database::Database& idealTestDatabase();

/// Renders the rectified left view of a generated scene from the database's own files (the
/// table and object OBJs, the index's ground-truth poses, P1 and the rectified left camera
/// X_TL R1^T of calibration.yml), independently of the generator's in-memory models: depth and
/// instance ids (table 1, objects 10 + object id). One offscreen renderer per process.
render::RenderResult renderLeftViewTruth(const database::Database& database,
                                         const database::SceneEntry& entry);

}  // namespace visgrab::test
