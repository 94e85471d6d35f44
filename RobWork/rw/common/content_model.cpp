#include "rw/common/content_model.hpp"

#include <algorithm>
#include <cctype>
#include <deque>
#include <map>
#include <utility>

#include "rw/common/strings.hpp"

namespace rw::common {

namespace {

/// Longest insertion looked for when explaining a missing element.
constexpr std::size_t kMaxInsertion = 4;
/// Nesting limit of groups (no stack overflow on a hostile model text).
constexpr int kMaxDepth = 64;

bool isNameStart(char c) {
  return std::isalpha(static_cast<unsigned char>(c)) != 0 || c == '_' || c == ':';
}

bool isNameChar(char c) {
  return isNameStart(c) || std::isdigit(static_cast<unsigned char>(c)) != 0 || c == '-' || c == '.';
}

std::string tag(const std::string& name) { return "<" + name + ">"; }

/// "<A>", "<A> and <B>", "<A>, <B> and <C>" (or with "or").
std::string tagList(const std::vector<std::string>& names, const char* conjunction = " and ") {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? conjunction : ", ";
    out += tag(names[i]);
  }
  return out;
}

}  // namespace

/// A Thompson automaton: states with epsilon moves and at most one move on an element name.
struct ContentModel::Automaton {
  struct State {
    std::vector<int> epsilon;
    int symbol = -1;
    int next = -1;
  };
  std::vector<State> states;
  std::vector<std::string> names;
  int start = 0;
  int accept = 0;

  using Set = std::vector<int>;  // sorted state numbers, epsilon-closed

  int add() {
    states.emplace_back();
    return static_cast<int>(states.size()) - 1;
  }

  int symbolOf(std::string_view name) const {
    const auto it = std::find(names.begin(), names.end(), name);
    return it == names.end() ? -1 : static_cast<int>(it - names.begin());
  }

  Set closure(std::vector<int> seeds) const {
    std::vector<bool> in(states.size(), false);
    Set out;
    while (!seeds.empty()) {
      const int s = seeds.back();
      seeds.pop_back();
      if (in[static_cast<std::size_t>(s)]) continue;
      in[static_cast<std::size_t>(s)] = true;
      out.push_back(s);
      for (const int e : states[static_cast<std::size_t>(s)].epsilon) seeds.push_back(e);
    }
    std::sort(out.begin(), out.end());
    return out;
  }

  Set step(const Set& from, int symbol) const {
    std::vector<int> seeds;
    for (const int s : from) {
      const State& st = states[static_cast<std::size_t>(s)];
      if (symbol >= 0 && st.symbol == symbol) seeds.push_back(st.next);
    }
    return closure(std::move(seeds));
  }

  Set run(const std::vector<std::string>& children, std::size_t count) const {
    Set set = closure({start});
    for (std::size_t i = 0; i < count && !set.empty(); ++i) {
      set = step(set, symbolOf(children[i]));
    }
    return set;
  }

  bool accepting(const Set& set) const {
    return std::binary_search(set.begin(), set.end(), accept);
  }

  std::vector<int> symbolsFrom(const Set& set) const {
    std::vector<int> out;
    for (const int s : set) {
      const int sym = states[static_cast<std::size_t>(s)].symbol;
      if (sym >= 0 && std::find(out.begin(), out.end(), sym) == out.end()) out.push_back(sym);
    }
    std::sort(out.begin(), out.end());
    return out;
  }

  /// Shortest list of names that, put after `from`, reaches a set where `done` holds (breadth
  /// first, up to kMaxInsertion names); nullopt if none.
  template <typename Done>
  std::optional<std::vector<std::string>> shortestPath(const Set& from, Done done) const {
    std::map<Set, std::vector<int>> seen;
    std::deque<Set> queue;
    seen.emplace(from, std::vector<int>{});
    queue.push_back(from);
    while (!queue.empty()) {
      const Set set = queue.front();
      queue.pop_front();
      const std::vector<int> path = seen.at(set);
      if (done(set)) {
        std::vector<std::string> out;
        for (const int sym : path) out.push_back(names[static_cast<std::size_t>(sym)]);
        return out;
      }
      if (path.size() >= kMaxInsertion) continue;
      for (const int sym : symbolsFrom(set)) {
        Set next = step(set, sym);
        if (next.empty() || seen.count(next) > 0) continue;
        std::vector<int> longer = path;
        longer.push_back(sym);
        seen.emplace(next, std::move(longer));
        queue.push_back(std::move(next));
      }
    }
    return std::nullopt;
  }
};

namespace {

/// "<A>" or, when any of several names would do, "one of <A>, <B> or <C>": the names that, put
/// after `from`, reach a set where `done` holds, when `path` (the shortest such insertion) is one
/// name long; `path` itself otherwise.
template <typename Done>
std::string insertionText(const ContentModel::Automaton& a,
                          const ContentModel::Automaton::Set& from,
                          const std::vector<std::string>& path, Done done) {
  if (path.size() != 1) return tagList(path);
  std::vector<std::string> options;
  for (const int sym : a.symbolsFrom(from)) {
    if (done(a.step(from, sym))) options.push_back(a.names[static_cast<std::size_t>(sym)]);
  }
  if (options.size() < 2) return tagList(path);
  return "one of " + tagList(options, " or ");
}

/// Recursive descent over the model text, building automaton fragments (start, end).
class ModelParser {
 public:
  ModelParser(std::string_view text, ContentModel::Automaton& a) : text_(text), a_(a) {}

  bool parse(std::pair<int, int>& whole) {
    skipBlanks();
    if (!item(whole, 0)) return false;
    skipBlanks();
    return pos_ == text_.size();
  }

 private:
  void skipBlanks() {
    while (pos_ < text_.size() && std::isspace(static_cast<unsigned char>(text_[pos_])) != 0) {
      ++pos_;
    }
  }

  bool item(std::pair<int, int>& frag, int depth) {
    if (depth > kMaxDepth || pos_ >= text_.size()) return false;
    if (text_[pos_] == '(') {
      if (!group(frag, depth + 1)) return false;
    } else if (isNameStart(text_[pos_])) {
      const std::size_t begin = pos_;
      while (pos_ < text_.size() && isNameChar(text_[pos_])) ++pos_;
      const std::string name(text_.substr(begin, pos_ - begin));
      int sym = a_.symbolOf(name);
      if (sym < 0) {
        a_.names.push_back(name);
        sym = static_cast<int>(a_.names.size()) - 1;
      }
      const int s = a_.add();
      const int e = a_.add();
      a_.states[static_cast<std::size_t>(s)].symbol = sym;
      a_.states[static_cast<std::size_t>(s)].next = e;
      frag = {s, e};
    } else {
      return false;
    }
    skipBlanks();
    if (pos_ < text_.size() && (text_[pos_] == '?' || text_[pos_] == '*' || text_[pos_] == '+')) {
      frag = quantified(frag, text_[pos_++]);
      skipBlanks();
    }
    return true;
  }

  std::pair<int, int> quantified(std::pair<int, int> f, char q) {
    const int s = a_.add();
    const int e = a_.add();
    auto eps = [&](int from, int to) {
      a_.states[static_cast<std::size_t>(from)].epsilon.push_back(to);
    };
    eps(s, f.first);
    eps(f.second, e);
    if (q == '?' || q == '*') eps(s, e);
    if (q == '*' || q == '+') eps(f.second, f.first);
    return {s, e};
  }

  bool group(std::pair<int, int>& frag, int depth) {
    ++pos_;  // '('
    skipBlanks();
    std::vector<std::pair<int, int>> parts;
    char separator = 0;
    while (true) {
      std::pair<int, int> part;
      if (!item(part, depth)) return false;
      parts.push_back(part);
      if (pos_ >= text_.size()) return false;
      const char c = text_[pos_];
      if (c == ')') {
        ++pos_;
        break;
      }
      if ((c != ',' && c != '|') || (separator != 0 && c != separator)) return false;
      separator = c;
      ++pos_;
      skipBlanks();
    }
    const int s = a_.add();
    const int e = a_.add();
    auto eps = [&](int from, int to) {
      a_.states[static_cast<std::size_t>(from)].epsilon.push_back(to);
    };
    if (separator == '|') {
      for (const auto& p : parts) {
        eps(s, p.first);
        eps(p.second, e);
      }
    } else {
      int at = s;
      for (const auto& p : parts) {
        eps(at, p.first);
        at = p.second;
      }
      eps(at, e);
    }
    frag = {s, e};
    return true;
  }

  std::string_view text_;
  std::size_t pos_ = 0;
  ContentModel::Automaton& a_;
};

}  // namespace

ContentModel::ContentModel(std::unique_ptr<Automaton> automaton) : a_(std::move(automaton)) {}
ContentModel::ContentModel(ContentModel&&) noexcept = default;
ContentModel& ContentModel::operator=(ContentModel&&) noexcept = default;
ContentModel::~ContentModel() = default;

std::optional<ContentModel> ContentModel::parse(std::string_view text) {
  auto a = std::make_unique<Automaton>();
  std::pair<int, int> whole;
  if (!ModelParser(text, *a).parse(whole)) return std::nullopt;
  a->start = whole.first;
  a->accept = whole.second;
  return ContentModel(std::move(a));
}

const std::vector<std::string>& ContentModel::names() const { return a_->names; }

bool ContentModel::accepts(const std::vector<std::string>& children) const {
  return a_->accepting(a_->run(children, children.size()));
}

std::optional<std::size_t> ContentModel::firstRejected(
    const std::vector<std::string>& children) const {
  Automaton::Set set = a_->closure({a_->start});
  for (std::size_t i = 0; i < children.size(); ++i) {
    set = a_->step(set, a_->symbolOf(children[i]));
    if (set.empty()) return i;
  }
  return std::nullopt;
}

std::vector<std::string> ContentModel::allowedAfter(
    const std::vector<std::string>& children) const {
  std::vector<std::string> out;
  for (const int sym : a_->symbolsFrom(a_->run(children, children.size()))) {
    out.push_back(a_->names[static_cast<std::size_t>(sym)]);
  }
  return out;
}

std::string ContentModel::explain(const std::vector<std::string>& children,
                                  const std::string& parent, std::size_t* rejected) const {
  const Automaton& a = *a_;
  const auto k = firstRejected(children);
  if (rejected != nullptr) *rejected = k.value_or(children.size());
  if (!k) {
    const Automaton::Set end = a.run(children, children.size());
    if (a.accepting(end)) return {};
    const auto missing =
        a.shortestPath(end, [&](const Automaton::Set& s) { return a.accepting(s); });
    if (!missing || missing->empty()) return "incomplete content in " + parent;
    return "missing " +
           insertionText(a, end, *missing,
                         [&](const Automaton::Set& s) { return a.accepting(s); }) +
           " (required " + (children.empty() ? "in " + parent : "after " + tag(children.back())) +
           ")";
  }
  const std::string& x = children[*k];
  const int symbol = a.symbolOf(x);
  const std::vector<std::string> before(children.begin(),
                                        children.begin() + static_cast<std::ptrdiff_t>(*k));
  const Automaton::Set here = a.run(children, *k);
  if (symbol < 0) {
    std::string message = tag(x) + " is not allowed in " + parent;
    const std::string_view best = closestMatch(x, a.names);
    if (!best.empty()) message += "; did you mean " + tag(std::string(best)) + "?";
    const std::vector<std::string> next = allowedAfter(before);
    message += next.empty() ? " (no further element is allowed here)"
                            : " (expected " + tagList(next, " or ") + " here)";
    return message;
  }
  const auto reaches = [&](const Automaton::Set& s) { return !a.step(s, symbol).empty(); };
  // Given again where the model allows it only once.
  for (std::size_t j = *k; j-- > 0;) {
    if (children[j] != x) continue;
    const Automaton::Set afterFirst = a.run(children, j + 1);
    if (!a.shortestPath(afterFirst, reaches)) {
      return tag(x) + " is given twice; " + parent + " allows only one";
    }
    break;
  }
  if (const auto insertion = a.shortestPath(here, reaches); insertion && !insertion->empty()) {
    const bool givenLater = std::all_of(insertion->begin(), insertion->end(), [&](const auto& n) {
      return std::find(children.begin() + static_cast<std::ptrdiff_t>(*k) + 1, children.end(), n) !=
             children.end();
    });
    if (givenLater) return tag(x) + " is out of order: it must come after " + tagList(*insertion);
    return "missing " + insertionText(a, here, *insertion, reaches) + " (required before " +
           tag(x) + ")";
  }
  // The latest place it could have had: right before the child it must precede.
  for (std::size_t i = *k; i-- > 0;) {
    if (!a.step(a.run(children, i), symbol).empty()) {
      return tag(x) + " is out of order: it must come before " + tag(children[i]);
    }
  }
  const std::vector<std::string> next = allowedAfter(before);
  return tag(x) + " is not allowed here in " + parent +
         (next.empty() ? std::string("; no further element is allowed")
                       : "; expected " + tagList(next, " or "));
}

}  // namespace rw::common
