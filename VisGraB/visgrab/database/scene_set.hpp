#pragma once

#include <array>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

/// The VisGraB scene database: scene set and conditions, filters, calibration, index and the
/// Database API (also over the original VisGraB benchmark manifest).
namespace visgrab::database {

/// Number of objects in the database (ids 1..kObjectCount).
inline constexpr int kObjectCount = 18;
/// Number of object pairs in the double-object scenes (letters a..i).
inline constexpr int kPairCount = 9;
/// Poses per object and placements per pair (indices 1..kPosesPerSubject).
inline constexpr int kPosesPerSubject = 8;
/// Number of scenes: 2 x (18 x 8 + 9 x 8).
inline constexpr int kSceneCount = 2 * (kObjectCount + kPairCount) * kPosesPerSubject;

/// The objects' names, index = object id - 1 (alphabetical, as in the paper's tables).
inline constexpr std::array<std::string_view, kObjectCount> kObjectNames = {
    "amicelli", "breadbox",     "burti",     "cleaningbottle", "cocacola", "corny",
    "denkmit",  "greencup",     "icecoffee", "marmelade",      "peachcan", "pure",
    "saltbox",  "saltcylinder", "sucker",    "tomato",         "waterjug", "whitecup"};

/// One object pair of the double-object scenes.
struct ObjectPair {
  /// The paper's letter, 'a'..'i'.
  char letter;
  /// Object id of the first object (the one named first in the original folder name).
  int first;
  /// Object id of the second object.
  int second;
};

/// The nine pairs (paper Table 3): a 1-18, b 2-11, c 3-7, d 4-15, e 5-14, f 6-8, g 9-13,
/// h 10-12, i 16-17.
inline constexpr std::array<ObjectPair, kPairCount> kObjectPairs = {{{'a', 1, 18},
                                                                     {'b', 2, 11},
                                                                     {'c', 3, 7},
                                                                     {'d', 4, 15},
                                                                     {'e', 5, 14},
                                                                     {'f', 6, 8},
                                                                     {'g', 9, 13},
                                                                     {'h', 10, 12},
                                                                     {'i', 16, 17}}};

/// The table the objects stand on.
enum class Texture { kPlain, kTextured };
/// One object or a pair of objects.
enum class SceneKind { kSingle, kDouble };
/// How the object(s) are placed: standing/lying for single scenes (poses 1-4 / 5-8),
/// apart/close for double scenes (placements 1-4 / 5-8).
enum class Arrangement { kStanding, kLying, kApart, kClose };

/// Name used in ids, files and filters: "plain", "textured".
std::string_view toString(Texture texture);
/// Name used in ids, files and filters: "single", "double".
std::string_view toString(SceneKind kind);
/// Name used in files and filters: "standing", "lying", "apart", "close".
std::string_view toString(Arrangement arrangement);
/// Inverse of toString(Texture); nullopt for other text.
std::optional<Texture> textureFromString(std::string_view text);
/// Inverse of toString(SceneKind); nullopt for other text.
std::optional<SceneKind> sceneKindFromString(std::string_view text);
/// Inverse of toString(Arrangement); nullopt for other text.
std::optional<Arrangement> arrangementFromString(std::string_view text);

/// The name of object `id` (1..18). @throws std::out_of_range for other ids.
std::string_view objectName(int id);
/// The id of the object called `name` (exact, lower case); nullopt if there is none.
std::optional<int> objectIdByName(std::string_view name);
/// The pair with the given letter; nullopt unless 'a'..'i'.
std::optional<ObjectPair> pairByLetter(char letter);
/// The pair made of objects `a` and `b` (either order); nullopt if they are not a pair.
std::optional<ObjectPair> pairOfObjects(int a, int b);

/// The conditions of one scene, as used by the analyses to group results.
struct SceneConditions {
  /// Plain or textured (cluttered) table.
  Texture texture = Texture::kPlain;
  /// One or two objects.
  SceneKind kind = SceneKind::kSingle;
  /// Object ids: one for a single scene; two, in pair order (ObjectPair::first, second), for a
  /// double scene.
  std::vector<int> objects;
  /// Pose (single) or placement (double) index, 1..8.
  int pose = 1;

  /// Standing (poses 1-4), lying (5-8), apart (placements 1-4) or close (5-8).
  Arrangement arrangement() const;
  /// The pair of a double scene; nullopt for a single scene or an invalid object list.
  std::optional<ObjectPair> pair() const;
  /// Equal when all fields are equal.
  bool operator==(const SceneConditions& other) const = default;

  /// A single-object scene. Not validated (see validate()).
  static SceneConditions single(Texture texture, int object, int pose);
  /// A double-object scene of the pair with `letter`. @throws std::invalid_argument for an
  /// unknown letter.
  static SceneConditions pairScene(Texture texture, char letter, int pose);
};

/// The objects and pairs a database is made of: the benchmark's (kObjectNames, kObjectPairs) or
/// those of a user's object spec (`visgrab db generate --objects SPEC`). The functions below
/// without a catalog use ObjectCatalog::benchmark().
struct ObjectCatalog {
  /// One object: its id and lower-case name (letters, digits, '_').
  struct Object {
    /// Positive id.
    int id = 0;
    /// Name used in scene ids.
    std::string name;
    /// Equal when both fields are.
    bool operator==(const Object& other) const = default;
  };
  /// Objects in ascending id order (ids and names unique).
  std::vector<Object> objects;
  /// Pairs, letters 'a', 'b', ... in order; a user catalog orders them by (first, second).
  std::vector<ObjectPair> pairs;

  /// The benchmark's 18 objects and 9 pairs.
  static const ObjectCatalog& benchmark();
  /// A catalog of `objects` (any order) and `pairs` (object ids, first then second; any
  /// order): sorted, pair letters assigned 'a'...
  /// @throws std::invalid_argument for duplicate ids, names or pairs, a bad name, a pair of
  /// unknown objects or of one object, more than 26 pairs.
  static ObjectCatalog make(std::vector<Object> objects, std::vector<std::pair<int, int>> pairs);
  /// True for the benchmark's catalog (equal content).
  bool isBenchmark() const { return benchmark_; }
  /// The name of object `id`. @throws std::out_of_range for an unknown id.
  std::string_view name(int id) const;
  /// The id of the object called `name`; nullopt if there is none.
  std::optional<int> idByName(std::string_view name) const;
  /// The pair made of `a` and `b` (either order); nullopt if they are not a pair.
  std::optional<ObjectPair> pairOf(int a, int b) const;
  /// Equal when objects and pairs are.
  bool operator==(const ObjectCatalog& other) const;

 private:
  bool benchmark_ = false;  // set by benchmark() and make() when the content is the benchmark's
};

/// Why `conditions` do not describe a scene of the database (empty string when they do).
std::string validate(const SceneConditions& conditions);
/// Same, for a database of `catalog`'s objects.
std::string validate(const SceneConditions& conditions, const ObjectCatalog& catalog);

/// All 432 scenes in the fixed order: plain then textured; within each, the single scenes
/// (object 1..18, pose 1..8) then the double scenes (pair a..i, placement 1..8).
std::vector<SceneConditions> enumerateScenes();
/// The scenes of a database of `catalog`'s objects in the same order (plain, textured; the
/// objects by id, 8 poses each; the pairs in catalog order, 8 placements each).
std::vector<SceneConditions> enumerateScenes(const ObjectCatalog& catalog);

/// Position of valid `conditions` in enumerateScenes() (0..431). @throws std::invalid_argument
/// for invalid conditions.
int sceneIndex(const SceneConditions& conditions);
/// Position of `conditions` in enumerateScenes(catalog). @throws std::invalid_argument.
int sceneIndex(const SceneConditions& conditions, const ObjectCatalog& catalog);

/// The scene id, `<texture>/<kind>/<subject>/<NN>`: e.g. `textured/single/cocacola/03`,
/// `plain/double/cocacola_saltcylinder/06` (subject of a pair = both names joined by '_', in
/// pair order; NN = pose, two digits). @throws std::invalid_argument for invalid conditions.
std::string sceneIdOf(const SceneConditions& conditions);
/// The scene id with `catalog`'s object names. @throws std::invalid_argument.
std::string sceneIdOf(const SceneConditions& conditions, const ObjectCatalog& catalog);

/// Inverse of sceneIdOf (exact spelling only); nullopt if `id` is not a scene id.
std::optional<SceneConditions> parseSceneId(std::string_view id);
/// Inverse of sceneIdOf(conditions, catalog); nullopt if `id` is not a scene id of `catalog`.
std::optional<SceneConditions> parseSceneId(std::string_view id, const ObjectCatalog& catalog);

/// The id of the scene in the original database's folder layout (ExtendVisGrabTask):
/// `<textured|non-textured>/<objdir>/img_<NN>`, e.g. `textured/cocacola/img_03`,
/// `non-textured/cocacola_saltcylinder/img_06`. @throws std::invalid_argument for invalid
/// conditions.
std::string originalIdOf(const SceneConditions& conditions);

/// Inverse of originalIdOf; nullopt if `id` is not of that form.
std::optional<SceneConditions> parseOriginalId(std::string_view id);

/// A one-line, human-readable description: "textured, single, standing, object 5 cocacola,
/// pose 3" or "plain, double, close, pair e: 5 cocacola + 14 saltcylinder, placement 6".
std::string describe(const SceneConditions& conditions);
/// The same description with `catalog`'s names (a user pair: "pair a: 40 mug + 41 jar").
std::string describe(const SceneConditions& conditions, const ObjectCatalog& catalog);

}  // namespace visgrab::database
