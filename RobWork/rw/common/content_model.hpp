#pragma once

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace rw::common {

/// An XML element's content model as a schema validator prints it (Xerces:
/// "(PreShape*,Closing,TauMax?,ContactIK?)": names, ',' for a sequence, '|' for a choice, '?',
/// '*', '+' after a name or a group), turned into an automaton so that a rejected list of
/// children can be explained the way an author thinks of it: which required element is missing,
/// which one is out of order or given twice, and which names were meant.
class ContentModel {
 public:
  /// Parses `text`; nullopt if it is not a content model of that form.
  static std::optional<ContentModel> parse(std::string_view text);

  ContentModel(ContentModel&&) noexcept;
  ContentModel& operator=(ContentModel&&) noexcept;
  ~ContentModel();

  /// The element names the model mentions, in order of first mention.
  const std::vector<std::string>& names() const;
  /// True if `children` (element names, in order) is a complete content.
  bool accepts(const std::vector<std::string>& children) const;
  /// Index of the first child that cannot follow the ones before it; nullopt if every child can
  /// (the content may still be incomplete).
  std::optional<std::size_t> firstRejected(const std::vector<std::string>& children) const;
  /// The names that may come after `children` (a valid beginning), in model order.
  std::vector<std::string> allowedAfter(const std::vector<std::string>& children) const;

  /// What is wrong with `children` inside `parent` (e.g. "<GraspDescription>"), in one phrase:
  ///  - a child the model does not mention: "<TauMx> is not allowed in <P>; did you mean
  ///    <TauMax>? (expected one of: ...)";
  ///  - required elements left out before it: "missing <Closing> (required before <TauMax>)";
  ///  - a child given more often than allowed: "<TauMax> is given twice; <P> allows it once";
  ///  - a child after elements it must precede: "<PreShape> is out of order: it must come
  ///    before <Closing>";
  ///  - required elements left out at the end: "missing <TauMax> (required after <Closing>)".
  /// `rejected` is set to the index of the child the message is about (children.size() for a
  /// message about the end). Empty if `children` is a complete content.
  std::string explain(const std::vector<std::string>& children, const std::string& parent,
                      std::size_t* rejected = nullptr) const;

  /// The automaton (defined in content_model.cpp only).
  struct Automaton;

 private:
  explicit ContentModel(std::unique_ptr<Automaton> automaton);
  std::unique_ptr<Automaton> a_;
};

}  // namespace rw::common
