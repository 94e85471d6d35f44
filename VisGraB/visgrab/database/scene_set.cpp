#include "visgrab/database/scene_set.hpp"

#include <algorithm>
#include <charconv>
#include <stdexcept>
#include <utility>

#include "rw/common/strings.hpp"

namespace visgrab::database {

namespace {

constexpr std::array<std::string_view, 2> kTextureNames = {"plain", "textured"};
static_assert(kTextureNames.size() == static_cast<std::size_t>(Texture::kTextured) + 1);
constexpr std::array<std::string_view, 2> kKindNames = {"single", "double"};
static_assert(kKindNames.size() == static_cast<std::size_t>(SceneKind::kDouble) + 1);
constexpr std::array<std::string_view, 4> kArrangementNames = {"standing", "lying", "apart",
                                                               "close"};
static_assert(kArrangementNames.size() == static_cast<std::size_t>(Arrangement::kClose) + 1);
// Folder names of the textures in the original database.
constexpr std::array<std::string_view, 2> kOriginalTextureNames = {"non-textured", "textured"};
static_assert(kOriginalTextureNames.size() == kTextureNames.size());

template <typename Enum, std::size_t N>
std::optional<Enum> fromTable(const std::array<std::string_view, N>& table, std::string_view text) {
  for (std::size_t i = 0; i < N; ++i) {
    if (table[i] == text) return static_cast<Enum>(i);
  }
  return std::nullopt;
}

// Two-digit pose "01".."08".
std::string twoDigits(int pose) {
  std::string out = std::to_string(pose);
  return out.size() < 2 ? "0" + out : out;
}

std::optional<int> parsePose(std::string_view text) {
  if (text.size() != 2 || text[0] != '0') return std::nullopt;
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size()) return std::nullopt;
  if (value < 1 || value > kPosesPerSubject) return std::nullopt;
  return value;
}

// The folder name of the scene's object(s): "cocacola" or "cocacola_saltcylinder".
std::string subjectOf(const SceneConditions& c,
                      const ObjectCatalog& catalog = ObjectCatalog::benchmark()) {
  std::string subject(catalog.name(c.objects.at(0)));
  if (c.kind == SceneKind::kDouble) subject += "_" + std::string(catalog.name(c.objects.at(1)));
  return subject;
}

// Conditions for a subject folder name, texture and pose with a user catalog's names; nullopt
// if the subject is unknown. `kind`: which kind to look for (both when nullopt, single first).
std::optional<SceneConditions> fromUserSubject(Texture texture, std::string_view subject, int pose,
                                               const ObjectCatalog& catalog,
                                               std::optional<SceneKind> kind) {
  if (kind != SceneKind::kDouble) {
    if (const auto id = catalog.idByName(subject)) {
      return SceneConditions::single(texture, *id, pose);
    }
  }
  if (kind == SceneKind::kSingle) return std::nullopt;
  for (const ObjectPair& p : catalog.pairs) {
    if (std::string(catalog.name(p.first)) + "_" + std::string(catalog.name(p.second)) == subject) {
      return SceneConditions{texture, SceneKind::kDouble, {p.first, p.second}, pose};
    }
  }
  return std::nullopt;
}

// Conditions for a subject folder name, texture and pose; nullopt if the subject is unknown.
std::optional<SceneConditions> fromSubject(
    Texture texture, std::string_view subject, int pose,
    const ObjectCatalog& catalog = ObjectCatalog::benchmark(),
    std::optional<SceneKind> kind = std::nullopt) {
  if (!catalog.isBenchmark()) return fromUserSubject(texture, subject, pose, catalog, kind);
  if (const auto id = objectIdByName(subject)) return SceneConditions::single(texture, *id, pose);
  const auto underscore = subject.find('_');
  if (underscore == std::string_view::npos) return std::nullopt;
  const auto a = objectIdByName(subject.substr(0, underscore));
  const auto b = objectIdByName(subject.substr(underscore + 1));
  if (!a || !b) return std::nullopt;
  const auto pair = pairOfObjects(*a, *b);
  if (!pair || pair->first != *a) return std::nullopt;
  return SceneConditions::pairScene(texture, pair->letter, pose);
}

void requireValid(const SceneConditions& c) {
  const std::string why = validate(c);
  if (!why.empty()) throw std::invalid_argument("invalid scene conditions: " + why);
}

}  // namespace

std::string_view toString(Texture texture) {
  return kTextureNames.at(static_cast<std::size_t>(texture));
}
std::string_view toString(SceneKind kind) { return kKindNames.at(static_cast<std::size_t>(kind)); }
std::string_view toString(Arrangement arrangement) {
  return kArrangementNames.at(static_cast<std::size_t>(arrangement));
}
std::optional<Texture> textureFromString(std::string_view text) {
  return fromTable<Texture>(kTextureNames, text);
}
std::optional<SceneKind> sceneKindFromString(std::string_view text) {
  return fromTable<SceneKind>(kKindNames, text);
}
std::optional<Arrangement> arrangementFromString(std::string_view text) {
  return fromTable<Arrangement>(kArrangementNames, text);
}

std::string_view objectName(int id) {
  if (id < 1 || id > kObjectCount) {
    throw std::out_of_range("object id " + std::to_string(id) + " is not in 1.." +
                            std::to_string(kObjectCount));
  }
  return kObjectNames[static_cast<std::size_t>(id - 1)];
}

std::optional<int> objectIdByName(std::string_view name) {
  for (int i = 0; i < kObjectCount; ++i) {
    if (kObjectNames[static_cast<std::size_t>(i)] == name) return i + 1;
  }
  return std::nullopt;
}

std::optional<ObjectPair> pairByLetter(char letter) {
  for (const ObjectPair& p : kObjectPairs) {
    if (p.letter == letter) return p;
  }
  return std::nullopt;
}

std::optional<ObjectPair> pairOfObjects(int a, int b) {
  for (const ObjectPair& p : kObjectPairs) {
    if ((p.first == a && p.second == b) || (p.first == b && p.second == a)) return p;
  }
  return std::nullopt;
}

Arrangement SceneConditions::arrangement() const {
  const bool first = pose <= kPosesPerSubject / 2;
  if (kind == SceneKind::kSingle) return first ? Arrangement::kStanding : Arrangement::kLying;
  return first ? Arrangement::kApart : Arrangement::kClose;
}

std::optional<ObjectPair> SceneConditions::pair() const {
  if (kind != SceneKind::kDouble || objects.size() != 2) return std::nullopt;
  return pairOfObjects(objects[0], objects[1]);
}

SceneConditions SceneConditions::single(Texture texture, int object, int pose) {
  return SceneConditions{texture, SceneKind::kSingle, {object}, pose};
}

SceneConditions SceneConditions::pairScene(Texture texture, char letter, int pose) {
  const auto pair = pairByLetter(letter);
  if (!pair) {
    throw std::invalid_argument(std::string("unknown object pair '") + letter +
                                "' (expected a..i)");
  }
  return SceneConditions{texture, SceneKind::kDouble, {pair->first, pair->second}, pose};
}

std::string validate(const SceneConditions& c) { return validate(c, ObjectCatalog::benchmark()); }

namespace {

std::string validateBenchmark(const SceneConditions& c) {
  if (c.texture != Texture::kPlain && c.texture != Texture::kTextured) return "unknown texture";
  if (c.pose < 1 || c.pose > kPosesPerSubject) {
    return "pose " + std::to_string(c.pose) + " is not in 1.." + std::to_string(kPosesPerSubject);
  }
  for (int id : c.objects) {
    if (id < 1 || id > kObjectCount) {
      return "object id " + std::to_string(id) + " is not in 1.." + std::to_string(kObjectCount);
    }
  }
  if (c.kind == SceneKind::kSingle) {
    if (c.objects.size() != 1) {
      return "a single scene has 1 object, not " + std::to_string(c.objects.size());
    }
    return {};
  }
  if (c.kind != SceneKind::kDouble) return "unknown scene kind";
  if (c.objects.size() != 2) {
    return "a double scene has 2 objects, not " + std::to_string(c.objects.size());
  }
  const auto pair = pairOfObjects(c.objects[0], c.objects[1]);
  if (!pair) {
    return "objects " + std::to_string(c.objects[0]) + " and " + std::to_string(c.objects[1]) +
           " are not one of the pairs a..i";
  }
  if (pair->first != c.objects[0]) {
    return "the objects of pair " + std::string(1, pair->letter) + " are listed in the order " +
           std::to_string(pair->first) + ", " + std::to_string(pair->second);
  }
  return {};
}

}  // namespace

std::vector<SceneConditions> enumerateScenes() {
  std::vector<SceneConditions> scenes;
  scenes.reserve(kSceneCount);
  for (Texture texture : {Texture::kPlain, Texture::kTextured}) {
    for (int object = 1; object <= kObjectCount; ++object) {
      for (int pose = 1; pose <= kPosesPerSubject; ++pose) {
        scenes.push_back(SceneConditions::single(texture, object, pose));
      }
    }
    for (const ObjectPair& pair : kObjectPairs) {
      for (int pose = 1; pose <= kPosesPerSubject; ++pose) {
        scenes.push_back(SceneConditions::pairScene(texture, pair.letter, pose));
      }
    }
  }
  return scenes;
}

int sceneIndex(const SceneConditions& c) { return sceneIndex(c, ObjectCatalog::benchmark()); }

namespace {

int benchmarkSceneIndex(const SceneConditions& c) {
  constexpr int kPerTexture = (kObjectCount + kPairCount) * kPosesPerSubject;
  int index = c.texture == Texture::kTextured ? kPerTexture : 0;
  if (c.kind == SceneKind::kSingle) {
    index += (c.objects[0] - 1) * kPosesPerSubject;
  } else {
    index += kObjectCount * kPosesPerSubject + (c.pair()->letter - 'a') * kPosesPerSubject;
  }
  return index + c.pose - 1;
}

}  // namespace

std::string sceneIdOf(const SceneConditions& c) { return sceneIdOf(c, ObjectCatalog::benchmark()); }

std::string sceneIdOf(const SceneConditions& c, const ObjectCatalog& catalog) {
  const std::string why = validate(c, catalog);
  if (!why.empty()) throw std::invalid_argument("invalid scene conditions: " + why);
  return std::string(toString(c.texture)) + "/" + std::string(toString(c.kind)) + "/" +
         subjectOf(c, catalog) + "/" + twoDigits(c.pose);
}

std::optional<SceneConditions> parseSceneId(std::string_view id) {
  return parseSceneId(id, ObjectCatalog::benchmark());
}

std::optional<SceneConditions> parseSceneId(std::string_view id, const ObjectCatalog& catalog) {
  const auto parts = rw::common::split(id, '/');
  if (parts.size() != 4) return std::nullopt;
  const auto texture = textureFromString(parts[0]);
  const auto kind = sceneKindFromString(parts[1]);
  const auto pose = parsePose(parts[3]);
  if (!texture || !kind || !pose) return std::nullopt;
  auto c = fromSubject(*texture, parts[2], *pose, catalog, *kind);
  if (!c || c->kind != *kind) return std::nullopt;
  return c;
}

std::string originalIdOf(const SceneConditions& c) {
  requireValid(c);
  return std::string(kOriginalTextureNames[static_cast<std::size_t>(c.texture)]) + "/" +
         subjectOf(c) + "/img_" + twoDigits(c.pose);
}

std::optional<SceneConditions> parseOriginalId(std::string_view id) {
  const auto parts = rw::common::split(id, '/');
  if (parts.size() != 3 || parts[2].substr(0, 4) != "img_") return std::nullopt;
  const auto texture = fromTable<Texture>(kOriginalTextureNames, parts[0]);
  const auto pose = parsePose(parts[2].substr(4));
  if (!texture || !pose) return std::nullopt;
  return fromSubject(*texture, parts[1], *pose);
}

std::string describe(const SceneConditions& c) { return describe(c, ObjectCatalog::benchmark()); }

std::string describe(const SceneConditions& c, const ObjectCatalog& catalog) {
  if (!catalog.isBenchmark()) {
    std::string out = std::string(toString(c.texture)) + ", " + std::string(toString(c.kind)) +
                      ", " + std::string(toString(c.arrangement())) + ", ";
    if (!validate(c, catalog).empty()) return out + "invalid objects";
    auto named = [&catalog](int id) {
      return std::to_string(id) + " " + std::string(catalog.name(id));
    };
    if (c.kind == SceneKind::kSingle) {
      return out + "object " + named(c.objects[0]) + ", pose " + std::to_string(c.pose);
    }
    return out + "pair " + catalog.pairOf(c.objects[0], c.objects[1])->letter + ": " +
           named(c.objects[0]) + " + " + named(c.objects[1]) + ", placement " +
           std::to_string(c.pose);
  }
  std::string out = std::string(toString(c.texture)) + ", " + std::string(toString(c.kind)) + ", " +
                    std::string(toString(c.arrangement())) + ", ";
  if (c.kind == SceneKind::kSingle && c.objects.size() == 1) {
    out += "object " + std::to_string(c.objects[0]) + " " + std::string(objectName(c.objects[0])) +
           ", pose " + std::to_string(c.pose);
  } else if (const auto pair = c.pair()) {
    out += std::string("pair ") + pair->letter + ": " + std::to_string(c.objects[0]) + " " +
           std::string(objectName(c.objects[0])) + " + " + std::to_string(c.objects[1]) + " " +
           std::string(objectName(c.objects[1])) + ", placement " + std::to_string(c.pose);
  } else {
    out += "invalid objects";
  }
  return out;
}

const ObjectCatalog& ObjectCatalog::benchmark() {
  static const ObjectCatalog catalog = [] {
    ObjectCatalog c;
    for (int id = 1; id <= kObjectCount; ++id)
      c.objects.push_back({id, std::string(objectName(id))});
    c.pairs.assign(kObjectPairs.begin(), kObjectPairs.end());
    c.benchmark_ = true;
    return c;
  }();
  return catalog;
}

ObjectCatalog ObjectCatalog::make(std::vector<Object> objects,
                                  std::vector<std::pair<int, int>> pairs) {
  ObjectCatalog c;
  std::sort(objects.begin(), objects.end(),
            [](const Object& a, const Object& b) { return a.id < b.id; });
  for (std::size_t i = 0; i < objects.size(); ++i) {
    const Object& o = objects[i];
    const bool nameOk = !o.name.empty() && std::all_of(o.name.begin(), o.name.end(), [](char ch) {
      return (ch >= 'a' && ch <= 'z') || (ch >= '0' && ch <= '9') || ch == '_';
    });
    if (o.id < 1 || !nameOk) {
      throw std::invalid_argument("object catalog: bad object " + std::to_string(o.id) + " \"" +
                                  o.name + "\" (ids > 0, names of a-z, 0-9 and '_')");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (objects[j].id == o.id || objects[j].name == o.name) {
        throw std::invalid_argument("object catalog: duplicate object " + std::to_string(o.id) +
                                    " \"" + o.name + "\"");
      }
    }
  }
  c.objects = std::move(objects);
  std::sort(pairs.begin(), pairs.end());
  if (pairs.size() > 26) throw std::invalid_argument("object catalog: more than 26 pairs");
  for (std::size_t i = 0; i < pairs.size(); ++i) {
    const auto [a, b] = pairs[i];
    if (!c.idByName(c.name(a)) || !c.idByName(c.name(b)) || a == b) {
      throw std::invalid_argument("object catalog: bad pair " + std::to_string(a) + ", " +
                                  std::to_string(b));
    }
    if (c.pairOf(a, b)) {
      throw std::invalid_argument("object catalog: duplicate pair " + std::to_string(a) + ", " +
                                  std::to_string(b));
    }
    c.pairs.push_back({static_cast<char>('a' + i), a, b});
  }
  c.benchmark_ =
      c.objects == benchmark().objects && c.pairs.size() == benchmark().pairs.size() &&
      std::equal(c.pairs.begin(), c.pairs.end(), benchmark().pairs.begin(),
                 [](const ObjectPair& x, const ObjectPair& y) {
                   return x.letter == y.letter && x.first == y.first && x.second == y.second;
                 });
  return c;
}

std::string_view ObjectCatalog::name(int id) const {
  for (const Object& o : objects) {
    if (o.id == id) return o.name;
  }
  throw std::out_of_range("object id " + std::to_string(id) + " is not in the object catalog");
}

std::optional<int> ObjectCatalog::idByName(std::string_view text) const {
  for (const Object& o : objects) {
    if (o.name == text) return o.id;
  }
  return std::nullopt;
}

std::optional<ObjectPair> ObjectCatalog::pairOf(int a, int b) const {
  for (const ObjectPair& p : pairs) {
    if ((p.first == a && p.second == b) || (p.first == b && p.second == a)) return p;
  }
  return std::nullopt;
}

bool ObjectCatalog::operator==(const ObjectCatalog& other) const {
  return objects == other.objects && pairs.size() == other.pairs.size() &&
         std::equal(pairs.begin(), pairs.end(), other.pairs.begin(),
                    [](const ObjectPair& x, const ObjectPair& y) {
                      return x.letter == y.letter && x.first == y.first && x.second == y.second;
                    });
}

std::string validate(const SceneConditions& c, const ObjectCatalog& catalog) {
  if (catalog.isBenchmark()) return validateBenchmark(c);
  if (c.texture != Texture::kPlain && c.texture != Texture::kTextured) return "unknown texture";
  if (c.pose < 1 || c.pose > kPosesPerSubject) {
    return "pose " + std::to_string(c.pose) + " is not in 1.." + std::to_string(kPosesPerSubject);
  }
  for (int id : c.objects) {
    if (!std::any_of(catalog.objects.begin(), catalog.objects.end(),
                     [id](const ObjectCatalog::Object& o) { return o.id == id; })) {
      return "object id " + std::to_string(id) + " is not an object of the catalog";
    }
  }
  const std::size_t count = c.kind == SceneKind::kSingle ? 1 : 2;
  if (c.kind != SceneKind::kSingle && c.kind != SceneKind::kDouble) return "unknown scene kind";
  if (c.objects.size() != count) {
    return std::string("a ") +
           (count == 1 ? "single scene has 1 object" : "double scene has 2 objects") + ", not " +
           std::to_string(c.objects.size());
  }
  if (c.kind == SceneKind::kDouble) {
    const auto pair = catalog.pairOf(c.objects[0], c.objects[1]);
    if (!pair || pair->first != c.objects[0]) {
      return "objects " + std::to_string(c.objects[0]) + " and " + std::to_string(c.objects[1]) +
             " are not a pair of the catalog (in that order)";
    }
  }
  return {};
}

std::vector<SceneConditions> enumerateScenes(const ObjectCatalog& catalog) {
  if (catalog.isBenchmark()) return enumerateScenes();
  std::vector<SceneConditions> scenes;
  for (Texture texture : {Texture::kPlain, Texture::kTextured}) {
    for (const auto& object : catalog.objects) {
      for (int pose = 1; pose <= kPosesPerSubject; ++pose) {
        scenes.push_back(SceneConditions::single(texture, object.id, pose));
      }
    }
    for (const ObjectPair& pair : catalog.pairs) {
      for (int pose = 1; pose <= kPosesPerSubject; ++pose) {
        scenes.push_back(
            SceneConditions{texture, SceneKind::kDouble, {pair.first, pair.second}, pose});
      }
    }
  }
  return scenes;
}

int sceneIndex(const SceneConditions& c, const ObjectCatalog& catalog) {
  const std::string why = validate(c, catalog);
  if (!why.empty()) throw std::invalid_argument("invalid scene conditions: " + why);
  if (catalog.isBenchmark()) return benchmarkSceneIndex(c);
  const int subjects = static_cast<int>(catalog.objects.size() + catalog.pairs.size());
  int index = c.texture == Texture::kTextured ? subjects * kPosesPerSubject : 0;
  if (c.kind == SceneKind::kSingle) {
    for (std::size_t i = 0; i < catalog.objects.size(); ++i) {
      if (catalog.objects[i].id == c.objects[0]) index += static_cast<int>(i) * kPosesPerSubject;
    }
  } else {
    index += static_cast<int>(catalog.objects.size()) * kPosesPerSubject +
             (catalog.pairOf(c.objects[0], c.objects[1])->letter - 'a') * kPosesPerSubject;
  }
  return index + c.pose - 1;
}

}  // namespace visgrab::database
