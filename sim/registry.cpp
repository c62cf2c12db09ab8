#include "sim/registry.h"

#include <algorithm>

#include "sim/config/config_node.h"

namespace tcpmsim {

void KindRegistry::add_category(Category category) {
  for (const auto& existing : categories_) {
    if (existing.name == category.name)
      throw std::logic_error("the category '" + category.name + "' is registered twice");
  }
  categories_.push_back(std::move(category));
  std::stable_sort(categories_.begin(), categories_.end(),
                   [](const Category& a, const Category& b) {
                     return a.top_level() != b.top_level() ? a.top_level() : a.order < b.order;
                   });
}

void KindRegistry::add(Kind kind) {
  category(kind.category);  // must exist
  if (find(kind.category, kind.name))
    throw std::logic_error("the kind '" + kind.name + "' of '" + kind.category +
                           "' is registered twice");
  kinds_.push_back(std::move(kind));
}

const Category& KindRegistry::category(std::string_view name) const {
  for (const auto& category : categories_) {
    if (category.name == name) return category;
  }
  throw std::logic_error("no category '" + std::string(name) + "' is registered");
}

std::vector<const Kind*> KindRegistry::kinds(std::string_view category) const {
  std::vector<const Kind*> found;
  for (const auto& kind : kinds_) {
    if (kind.category == category) found.push_back(&kind);
  }
  return found;
}

std::vector<std::string> KindRegistry::kind_names(std::string_view category) const {
  std::vector<std::string> names;
  for (const Kind* kind : kinds(category)) names.push_back(kind->name);
  return names;
}

const Kind* KindRegistry::find(std::string_view category, std::string_view name) const {
  for (const auto& kind : kinds_) {
    if (kind.category == category && kind.name == name) return &kind;
  }
  return nullptr;
}

const Kind& KindRegistry::registered(std::string_view category, std::string_view name) const {
  if (const Kind* kind = find(category, name)) return *kind;
  throw std::logic_error("no kind '" + std::string(name) + "' of '" + std::string(category) +
                         "' is registered");
}

const Kind& KindRegistry::select(std::string_view category_name, const ConfigNode& node) const {
  const Category& category = this->category(category_name);
  const auto names = kind_names(category_name);
  if (!category.top_level()) {
    std::string listed;
    for (const auto& name : names) listed += (listed.empty() ? "" : ", ") + name;
    node.mark_part(category.name + ": " + listed);
  }
  std::string name;
  if (category.selector.empty()) {
    name = category.default_kind.empty() ? names.front() : category.default_kind;
  } else if (category.default_kind.empty()) {
    name = node.choice(category.selector, names);
  } else {
    name = node.choice_or(category.selector, names, category.default_kind);
  }
  if (!category.selector.empty() && names.size() > 1)
    node.mark_variant(category.name, category.selector, name);
  return registered(category_name, name);
}

}  // namespace tcpmsim
