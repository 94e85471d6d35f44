#pragma once

#include <compare>
#include <cstddef>
#include <cstdint>
#include <ostream>
#include <string>

namespace rwsim::dynamics {

/// An index into one table of a DynamicWorkCell; `Tag` keeps the tables apart, so a body id
/// cannot be passed where a device id is expected. Default-constructed it is none().
template <class Tag>
class Id {
 public:
  /// The invalid id ("no such entry").
  constexpr Id() = default;
  /// The id of entry `index` of its table.
  constexpr explicit Id(std::size_t index) : index_(static_cast<std::int32_t>(index)) {}
  /// The invalid id.
  static constexpr Id none() { return Id(); }
  /// True when this names an entry.
  constexpr bool valid() const { return index_ >= 0; }
  /// Position in the table. Precondition: valid().
  constexpr std::size_t index() const { return static_cast<std::size_t>(index_); }
  /// Ids compare by index; none() sorts before every valid id.
  friend constexpr auto operator<=>(Id, Id) = default;
  /// Writes the index, or "none".
  friend std::ostream& operator<<(std::ostream& out, Id id) {
    if (!id.valid()) return out << "none";
    return out << id.index_;
  }

 private:
  std::int32_t index_ = -1;
};

/// The index of `id` as text, or "none".
template <class Tag>
std::string toString(Id<Tag> id) {
  return id.valid() ? std::to_string(id.index()) : std::string("none");
}

/// Tag of BodyId.
struct BodyTag {};
/// Tag of DeviceId.
struct DeviceTag {};

/// Index of a body in DynamicWorkCell::bodies().
using BodyId = Id<BodyTag>;
/// Index of a rigid device in DynamicWorkCell::devices().
using DeviceId = Id<DeviceTag>;

}  // namespace rwsim::dynamics
