#include "propulsion_estimator/common/name_list.h"

namespace propulsion_estimator {

std::string nameList(const std::vector<std::string>& names, std::size_t shown) {
  std::string text;
  const std::size_t listed = names.size() > shown + 1 ? shown : names.size();
  for (std::size_t k = 0; k < listed; ++k) {
    text += (k == 0 ? "" : k + 1 == names.size() ? " and " : ", ") + names[k];
  }
  if (listed < names.size()) text += " and " + std::to_string(names.size() - listed) + " more";
  return text;
}

std::string joined(const std::vector<std::string>& items, const std::string& separator) {
  std::string text;
  for (std::size_t k = 0; k < items.size(); ++k) text += (k == 0 ? "" : separator) + items[k];
  return text;
}

}  // namespace propulsion_estimator
