#pragma once
// A non-empty JSON array of objects, each with a unique "name": the scene
// lists of a regression suite (regress/suite.cpp) and of a benchmark set
// (measure/bench_set.cpp). A repeated name is an error at the later item's
// /name that points at the earlier one.
#include <string>
#include <utility>
#include <vector>

#include "common/json_reader.h"

namespace vesper {

// `parse(element)` reads one item (a type with a `name` member).
template <class Item, class Parse>
std::vector<Item> read_named_items(const JsonReader& array, Parse parse) {
  if (array.size() == 0) array.fail("expected at least one scene");
  std::vector<Item> items;
  for (size_t i = 0; i < array.size(); ++i) {
    Item item = parse(array.element(i));
    for (size_t j = 0; j < items.size(); ++j)
      if (items[j].name == item.name)
        array.element(i).fail_key("name", "duplicate scene name \"" + item.name +
                                              "\" (already at " +
                                              json_pointer_append(array.path(), j) + ")");
    items.push_back(std::move(item));
  }
  return items;
}

}  // namespace vesper
