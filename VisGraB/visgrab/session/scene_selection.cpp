#include "visgrab/session/scene_selection.hpp"

#include <stdexcept>

#include "visgrab/database/scene_filter.hpp"

namespace visgrab::session {

std::vector<const database::SceneEntry*> selectScenes(const database::Database& db,
                                                      const std::string& filterText) {
  try {
    return db.filter(filterText.empty() ? database::SceneFilter()
                                        : database::SceneFilter::parse(filterText));
  } catch (const database::FilterError& e) {
    throw std::invalid_argument(std::string("scene filter: ") + e.what());
  }
}

}  // namespace visgrab::session
