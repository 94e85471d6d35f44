#pragma once

#include <string>
#include <vector>

#include "visgrab/database/database.hpp"

namespace visgrab::session {

/// The scenes of `db` that the scene filter `filterText` selects (docs/database-format.md), in
/// database order; an empty text selects all. The benchmark runs these scenes in this order.
/// @throws std::invalid_argument "scene filter: ..." naming the bad word.
std::vector<const database::SceneEntry*> selectScenes(const database::Database& db,
                                                      const std::string& filterText);

}  // namespace visgrab::session
