#include "visgrab/database/scene_filter.hpp"

#include <algorithm>
#include <charconv>
#include <optional>

#include "rw/common/strings.hpp"
#include "rw/common/xml_tree.hpp"

namespace visgrab::database {

namespace {

constexpr std::string_view kExpected =
    "expected plain, textured, single, double, standing, lying, apart, close, an object name, "
    "all, an id glob (with / * ?) or KEY=VALUE with KEY one of texture, kind, arrangement, "
    "object, pair, pose, id";

std::optional<Texture> textureWord(std::string_view w) {
  if (w == "non-textured" || w == "nontextured") return Texture::kPlain;
  return textureFromString(w);
}

std::optional<Arrangement> arrangementWord(std::string_view w) {
  if (w == "laying") return Arrangement::kLying;
  if (w == "far") return Arrangement::kApart;
  if (w == "touching") return Arrangement::kClose;
  return arrangementFromString(w);
}

std::optional<int> smallInt(std::string_view text) {
  int value = 0;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (ec != std::errc() || end != text.data() + text.size() || text.empty()) return std::nullopt;
  return value;
}

std::string suggestion(std::string_view word) {
  std::vector<std::string_view> known = {
      "plain", "textured", "single", "double", "standing", "lying", "apart", "close",
      "all",   "texture",  "kind",   "object", "pair",     "pose",  "id",    "arrangement"};
  known.insert(known.end(), kObjectNames.begin(), kObjectNames.end());
  std::string_view best;
  std::size_t bestDistance = 3;
  for (std::string_view k : known) {
    const std::size_t d = rw::common::editDistance(word, k);
    if (d < bestDistance) {
      bestDistance = d;
      best = k;
    }
  }
  return best.empty() ? std::string() : " (did you mean \"" + std::string(best) + "\"?)";
}

[[noreturn]] void fail(std::string_view whole, const std::string& what) {
  throw FilterError("scene filter \"" + std::string(whole) + "\": " + what);
}

}  // namespace

bool globMatch(std::string_view pattern, std::string_view text) {
  std::size_t p = 0;
  std::size_t t = 0;
  std::size_t starP = std::string_view::npos;
  std::size_t starT = 0;
  while (t < text.size()) {
    if (p < pattern.size() && (pattern[p] == '?' || pattern[p] == text[t])) {
      ++p;
      ++t;
    } else if (p < pattern.size() && pattern[p] == '*') {
      starP = p++;
      starT = t;
    } else if (starP != std::string_view::npos) {
      p = starP + 1;
      t = ++starT;
    } else {
      return false;
    }
  }
  while (p < pattern.size() && pattern[p] == '*') ++p;
  return p == pattern.size();
}

SceneFilter::Term SceneFilter::parseTerm(std::string_view text, std::string_view whole,
                                         const ObjectCatalog& catalog) {
  Term term;
  std::string_view word = rw::common::trimXmlSpace(text);
  if (word.empty()) fail(whole, "empty term (two separators in a row, or one at an end)");
  if (word.front() == '!') {
    term.negated = true;
    word = rw::common::trimXmlSpace(word.substr(1));
    if (word.empty()) fail(whole, "'!' must be followed by a term");
  }
  const auto equals = word.find('=');
  if (equals == std::string_view::npos) {
    if (word == "all" || word == "*") {
      term.type = Term::Type::kAll;
    } else if (const auto t = textureWord(word)) {
      term.type = Term::Type::kTexture;
      term.value = static_cast<int>(*t);
    } else if (const auto k = sceneKindFromString(word)) {
      term.type = Term::Type::kKind;
      term.value = static_cast<int>(*k);
    } else if (const auto a = arrangementWord(word)) {
      term.type = Term::Type::kArrangement;
      term.value = static_cast<int>(*a);
    } else if (const auto o = catalog.idByName(word)) {
      term.type = Term::Type::kObject;
      term.value = *o;
    } else if (word.find_first_of("/*?") != std::string_view::npos) {
      term.type = Term::Type::kIdGlob;
      term.glob = std::string(word);
    } else {
      fail(whole, "unknown word \"" + std::string(word) + "\"" + suggestion(word) + "; " +
                      std::string(kExpected));
    }
    return term;
  }
  const std::string_view key = rw::common::trimXmlSpace(word.substr(0, equals));
  const std::string_view value = rw::common::trimXmlSpace(word.substr(equals + 1));
  const auto badValue = [&](std::string_view expected) {
    fail(whole, "bad value \"" + std::string(value) + "\" for " + std::string(key) +
                    "=; expected " + std::string(expected));
  };
  if (key == "id") {
    if (value.empty()) badValue("a scene id or glob");
    term.type = Term::Type::kIdGlob;
    term.glob = std::string(value);
  } else if (key == "texture") {
    const auto t = textureWord(value);
    if (!t) badValue("plain or textured");
    term.type = Term::Type::kTexture;
    term.value = static_cast<int>(*t);
  } else if (key == "kind") {
    const auto k = sceneKindFromString(value);
    if (!k) badValue("single or double");
    term.type = Term::Type::kKind;
    term.value = static_cast<int>(*k);
  } else if (key == "arrangement") {
    const auto a = arrangementWord(value);
    if (!a) badValue("standing, lying, apart or close");
    term.type = Term::Type::kArrangement;
    term.value = static_cast<int>(*a);
  } else if (key == "object") {
    auto id = smallInt(value);
    if (!id) id = catalog.idByName(value);
    const bool known =
        id && std::any_of(catalog.objects.begin(), catalog.objects.end(),
                          [&](const ObjectCatalog::Object& o) { return o.id == *id; });
    if (!known) {
      badValue(catalog.isBenchmark() ? "an object id 1..18 or an object name"
                                     : "an object id or name of this database's objects");
    }
    term.type = Term::Type::kObject;
    term.value = *id;
  } else if (key == "pair") {
    const auto pair = std::find_if(
        catalog.pairs.begin(), catalog.pairs.end(),
        [&](const ObjectPair& p) { return value.size() == 1 && p.letter == value[0]; });
    if (pair == catalog.pairs.end()) {
      badValue(catalog.pairs.empty()
                   ? std::string("none: this database has no pairs")
                   : "a pair letter a.." + std::string(1, catalog.pairs.back().letter));
    }
    term.type = Term::Type::kPair;
    term.value = value[0];
    term.first = pair->first;
    term.second = pair->second;
  } else if (key == "pose") {
    const auto pose = smallInt(value);
    if (!pose || *pose < 1 || *pose > kPosesPerSubject) badValue("a pose index 1..8");
    term.type = Term::Type::kPose;
    term.value = *pose;
  } else {
    fail(whole, "unknown key \"" + std::string(key) + "\"" + suggestion(key) +
                    "; expected texture, kind, arrangement, object, pair, pose or id");
  }
  return term;
}

SceneFilter SceneFilter::parse(std::string_view text) {
  return parse(text, ObjectCatalog::benchmark());
}

SceneFilter SceneFilter::parse(const std::vector<std::string>& texts) {
  return parse(texts, ObjectCatalog::benchmark());
}

SceneFilter SceneFilter::parse(std::string_view text, const ObjectCatalog& catalog) {
  SceneFilter filter;
  if (rw::common::trimXmlSpace(text).empty()) return filter;
  bool all = false;
  for (std::string_view alternative : rw::common::split(text, ';')) {
    Conjunction conjunction;
    for (std::string_view term : rw::common::split(alternative, ',')) {
      conjunction.push_back(parseTerm(term, text, catalog));
    }
    const bool everything = std::all_of(conjunction.begin(), conjunction.end(), [](const Term& t) {
      return t.type == Term::Type::kAll && !t.negated;
    });
    all = all || everything;
    filter.alternatives_.push_back(std::move(conjunction));
  }
  if (all) filter.alternatives_.clear();
  return filter;
}

SceneFilter SceneFilter::parse(const std::vector<std::string>& texts,
                               const ObjectCatalog& catalog) {
  SceneFilter filter;
  for (const std::string& text : texts) {
    SceneFilter one = parse(text, catalog);
    if (one.selectsAll()) return one;
    filter.alternatives_.insert(filter.alternatives_.end(), one.alternatives_.begin(),
                                one.alternatives_.end());
  }
  return filter;
}

bool SceneFilter::matchesTerm(const Term& term, std::string_view id, const SceneConditions* c) {
  bool result = false;
  switch (term.type) {
    case Term::Type::kAll:
      result = true;
      break;
    case Term::Type::kIdGlob:
      result = globMatch(term.glob, id);
      break;
    case Term::Type::kTexture:
      result = c != nullptr && static_cast<int>(c->texture) == term.value;
      break;
    case Term::Type::kKind:
      result = c != nullptr && static_cast<int>(c->kind) == term.value;
      break;
    case Term::Type::kArrangement:
      result = c != nullptr && static_cast<int>(c->arrangement()) == term.value;
      break;
    case Term::Type::kObject:
      result = c != nullptr &&
               std::find(c->objects.begin(), c->objects.end(), term.value) != c->objects.end();
      break;
    case Term::Type::kPair:
      result = c != nullptr && c->kind == SceneKind::kDouble && c->objects.size() == 2 &&
               c->objects[0] == term.first && c->objects[1] == term.second;
      break;
    case Term::Type::kPose:
      result = c != nullptr && c->pose == term.value;
      break;
  }
  return term.negated ? !result : result;
}

bool SceneFilter::matches(std::string_view id, const SceneConditions* conditions) const {
  if (alternatives_.empty()) return true;
  return std::any_of(alternatives_.begin(), alternatives_.end(), [&](const Conjunction& terms) {
    return std::all_of(terms.begin(), terms.end(),
                       [&](const Term& t) { return matchesTerm(t, id, conditions); });
  });
}

std::string SceneFilter::termToString(const Term& term) {
  std::string out = term.negated ? "!" : "";
  switch (term.type) {
    case Term::Type::kAll:
      return out + "all";
    case Term::Type::kIdGlob:
      return out + "id=" + term.glob;
    case Term::Type::kTexture:
      return out + std::string(database::toString(static_cast<Texture>(term.value)));
    case Term::Type::kKind:
      return out + std::string(database::toString(static_cast<SceneKind>(term.value)));
    case Term::Type::kArrangement:
      return out + std::string(database::toString(static_cast<Arrangement>(term.value)));
    case Term::Type::kObject:
      return out + "object=" + std::to_string(term.value);
    case Term::Type::kPair:
      return out + "pair=" + std::string(1, static_cast<char>(term.value));
    case Term::Type::kPose:
      return out + "pose=" + std::to_string(term.value);
  }
  return out;
}

std::string SceneFilter::toString() const {
  if (alternatives_.empty()) return "all";
  std::string out;
  for (std::size_t i = 0; i < alternatives_.size(); ++i) {
    if (i > 0) out += ";";
    for (std::size_t j = 0; j < alternatives_[i].size(); ++j) {
      if (j > 0) out += ",";
      out += termToString(alternatives_[i][j]);
    }
  }
  return out;
}

}  // namespace visgrab::database
