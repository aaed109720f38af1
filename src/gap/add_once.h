// Lists that keep each value once (private to src/gap/): a replay's flagged channels and verdicts.
#pragma once

#include <algorithm>
#include <vector>

namespace propulsion_estimator {
namespace gap {

// Appends `value` to `list` unless it is there already.
template <typename T>
void addOnce(std::vector<T>* list, const T& value) {
  if (std::find(list->begin(), list->end(), value) == list->end()) list->push_back(value);
}

}  // namespace gap
}  // namespace propulsion_estimator
