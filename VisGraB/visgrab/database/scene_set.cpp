#include "visgrab/database/scene_set.hpp"

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
std::string subjectOf(const SceneConditions& c) {
  std::string subject(objectName(c.objects.at(0)));
  if (c.kind == SceneKind::kDouble) subject += "_" + std::string(objectName(c.objects.at(1)));
  return subject;
}

// Conditions for a subject folder name, texture and pose; nullopt if the subject is unknown.
std::optional<SceneConditions> fromSubject(Texture texture, std::string_view subject, int pose) {
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

std::string validate(const SceneConditions& c) {
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

int sceneIndex(const SceneConditions& c) {
  requireValid(c);
  constexpr int kPerTexture = (kObjectCount + kPairCount) * kPosesPerSubject;
  int index = c.texture == Texture::kTextured ? kPerTexture : 0;
  if (c.kind == SceneKind::kSingle) {
    index += (c.objects[0] - 1) * kPosesPerSubject;
  } else {
    index += kObjectCount * kPosesPerSubject + (c.pair()->letter - 'a') * kPosesPerSubject;
  }
  return index + c.pose - 1;
}

std::string sceneIdOf(const SceneConditions& c) {
  requireValid(c);
  return std::string(toString(c.texture)) + "/" + std::string(toString(c.kind)) + "/" +
         subjectOf(c) + "/" + twoDigits(c.pose);
}

std::optional<SceneConditions> parseSceneId(std::string_view id) {
  const auto parts = rw::common::split(id, '/');
  if (parts.size() != 4) return std::nullopt;
  const auto texture = textureFromString(parts[0]);
  const auto kind = sceneKindFromString(parts[1]);
  const auto pose = parsePose(parts[3]);
  if (!texture || !kind || !pose) return std::nullopt;
  auto c = fromSubject(*texture, parts[2], *pose);
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

std::string describe(const SceneConditions& c) {
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

}  // namespace visgrab::database
