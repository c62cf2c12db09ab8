#include "sim/io/input_descriptions.h"

#include <algorithm>
#include <cctype>

#include "sim/io/hdf5_files.h"

namespace tcpmsim {
namespace {

std::vector<std::string> text_array_attribute(const H5::H5Object& object, const std::string& name) {
  if (!object.attrExists(name)) return {};
  H5::Attribute attribute = object.openAttribute(name);
  // Read as pointers: fixed-length texts would be written past them.
  if (attribute.getTypeClass() != H5T_STRING || !attribute.getStrType().isVariableStr())
    throw H5::AttributeIException("text_array_attribute",
                                  "the attribute " + name + " is not variable-length text");
  const auto count = static_cast<std::size_t>(attribute.getSpace().getSimpleExtentNpoints());
  std::vector<char*> pointers(count, nullptr);
  attribute.read(attribute.getStrType(), pointers.data());
  std::vector<std::string> values(pointers.begin(), pointers.end());
  H5Dvlen_reclaim(attribute.getStrType().getId(), attribute.getSpace().getId(), H5P_DEFAULT,
                  pointers.data());
  return values;
}

// "segment2" before "segment10": digits compared as numbers.
bool natural_less(const std::string& a, const std::string& b) {
  std::size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) &&
        std::isdigit(static_cast<unsigned char>(b[j]))) {
      std::size_t ei = i, ej = j;
      while (ei < a.size() && std::isdigit(static_cast<unsigned char>(a[ei]))) ++ei;
      while (ej < b.size() && std::isdigit(static_cast<unsigned char>(b[ej]))) ++ej;
      const std::string na = a.substr(i, ei - i), nb = b.substr(j, ej - j);
      if (na.size() != nb.size()) return na.size() < nb.size();
      if (na != nb) return na < nb;
      i = ei, j = ej;
      continue;
    }
    if (a[i] != b[j]) return a[i] < b[j];
    ++i, ++j;
  }
  return a.size() - i < b.size() - j;
}

std::vector<std::string> member_names(const H5::Group& group) {
  std::vector<std::string> names;
  for (hsize_t k = 0; k < group.getNumObjs(); ++k) names.push_back(group.getObjnameByIdx(k));
  std::sort(names.begin(), names.end(), natural_less);
  return names;
}

// The paths of the groups that describe an input: a group with a `type` attribute, at any depth
// under /inputs ("b/drive.power" is the group b holding drive.power).
void collect_inputs(const H5::Group& group, const std::string& prefix,
                    std::vector<RecordedInput>& inputs) {
  for (const auto& name : member_names(group)) {
    if (group.childObjType(name) != H5O_TYPE_GROUP) continue;
    const H5::Group child = group.openGroup(name);
    const std::string path = prefix.empty() ? name : prefix + "/" + name;
    if (!child.attrExists("type")) {
      collect_inputs(child, path, inputs);
      continue;
    }
    inputs.push_back({path, units_of(child), read_signal_description(child),
                      text_array_attribute(child, "members")});
  }
}

}  // namespace

SignalDescription read_signal_description(const H5::Group& group) {
  SignalDescription description;
  description.type = read_text_attribute(group, "type");
  for (int k = 0; k < group.getNumAttrs(); ++k) {
    H5::Attribute attribute = group.openAttribute(static_cast<unsigned>(k));
    if (attribute.getTypeClass() != H5T_FLOAT && attribute.getTypeClass() != H5T_INTEGER) continue;
    require_single_value(attribute);
    double value = 0.0;
    attribute.read(H5::PredType::NATIVE_DOUBLE, &value);
    description.parameters.emplace_back(attribute.getName(), value);
  }
  for (const auto& name : member_names(group)) {
    if (group.childObjType(name) == H5O_TYPE_DATASET)
      description.arrays.emplace_back(name, read_doubles(group, name));
    else if (group.childObjType(name) == H5O_TYPE_GROUP)
      description.parts.push_back({name, read_signal_description(group.openGroup(name))});
  }
  return description;
}

std::vector<RecordedInput> read_record_inputs(const H5::H5File& file) {
  std::vector<RecordedInput> inputs;
  if (!file.nameExists("inputs")) return inputs;
  collect_inputs(file.openGroup("inputs"), "", inputs);
  return inputs;
}

}  // namespace tcpmsim
