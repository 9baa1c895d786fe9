#pragma once
// A list of AOV names (a scene's render.aovs, a farm job's "aovs"): each one
// of kAovNames, none twice; errors name the element's JSON path. Header-only
// so that the farm server checks a job's AOVs exactly as the renderer reads
// them, without linking the renderer.
#include <vector>

#include "common/json_reader.h"
#include "renderer/scene/aov_names.h"

namespace vesper {

inline std::vector<Aov> read_aov_list(const JsonReader& list) {
  list.expect_array();
  std::vector<Aov> aovs;
  for (size_t i = 0; i < list.size(); ++i) {
    const JsonReader e = list.element(i);
    const Aov aov = static_cast<Aov>(e.as_enum(kAovNames));
    for (size_t j = 0; j < aovs.size(); ++j)
      if (aovs[j] == aov)
        e.fail("duplicate AOV " + e.json().dump() + " (already at " +
               json_pointer_append(list.path(), j) + ")");
    aovs.push_back(aov);
  }
  return aovs;
}

}  // namespace vesper
