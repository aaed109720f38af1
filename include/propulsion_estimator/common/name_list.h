#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace propulsion_estimator {

/// Names joined for a message: "a", "a and b", "a, b and c" when there are at most `shown` + 1,
/// else the first `shown` and a count ("a, b and 3 more"). Throws nothing.
std::string nameList(const std::vector<std::string>& names, std::size_t shown);

/// `items` joined by `separator`: "a, b, c"; "" when empty. Throws nothing but std::bad_alloc.
std::string joined(const std::vector<std::string>& items, const std::string& separator = ", ");

}  // namespace propulsion_estimator
