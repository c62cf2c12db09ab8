#include "fmu/model_description.h"

#include <libxml/parser.h>
#include <libxml/tree.h>

#include <cctype>
#include <cmath>
#include <map>
#include <memory>
#include <set>
#include <sstream>
#include <string_view>

#include "sim/config/config_error.h"
#include "sim/value_check.h"

namespace tcpmsim::fmu {
namespace {

// XML text of `text`: XML 1.0 cannot hold control characters, so they (and a byte of no UTF-8
// sequence) are written as printable() writes them ("\x07"), then &, <, > and " as entities.
std::string escaped(const std::string& text) {
  std::string out;
  for (const char c : printable(text)) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string real(double value) {  // round-trips through text
  return number_text(value, 17);
}

const char* causality_name(FmuVariable::Causality causality) {
  switch (causality) {
    case FmuVariable::Causality::input:
      return "input";
    case FmuVariable::Causality::parameter:
      return "parameter";
    case FmuVariable::Causality::output:
      break;
  }
  return "output";
}

void write_units(std::ostream& xml, const FmuInterface& fmu, const UnitSystem& units) {
  std::set<std::string> names;
  for (const auto& variable : fmu.variables)
    if (!variable.unit.empty()) names.insert(variable.unit);
  xml << "  <UnitDefinitions>\n";
  for (const auto& name : names) {
    const SiBaseUnit base = units.si_base(name);
    xml << "    <Unit name=\"" << escaped(name) << "\"><BaseUnit";
    for (std::size_t k = 0; k < base.exponents.size(); ++k)
      if (base.exponents[k] != 0)
        xml << " " << SiBaseUnit::kSymbols[k] << "=\"" << base.exponents[k] << "\"";
    if (base.factor != 1.0) xml << " factor=\"" << real(base.factor) << "\"";
    if (base.offset != 0.0) xml << " offset=\"" << real(base.offset) << "\"";
    xml << "/></Unit>\n";
  }
  xml << "  </UnitDefinitions>\n";
}

void write_variable(std::ostream& xml, const FmuVariable& variable) {
  const bool output = variable.causality == FmuVariable::Causality::output;
  xml << "    <ScalarVariable name=\"" << escaped(variable.name) << "\" valueReference=\""
      << variable.value_reference << "\" causality=\"" << causality_name(variable.causality)
      << "\" variability=\""
      << (variable.causality == FmuVariable::Causality::parameter ? "fixed" : "continuous") << "\"";
  if (variable.causality == FmuVariable::Causality::parameter) xml << " initial=\"exact\"";
  if (output) xml << " initial=\"calculated\"";
  if (!variable.description.empty())
    xml << " description=\"" << escaped(variable.description) << "\"";
  xml << ">\n      <Real";
  if (!variable.unit.empty()) xml << " unit=\"" << escaped(variable.unit) << "\"";
  if (!output) xml << " start=\"" << real(variable.start) << "\"";
  if (variable.has_range)
    xml << " min=\"" << real(variable.min) << "\" max=\"" << real(variable.max) << "\"";
  xml << "/>\n    </ScalarVariable>\n";
}

}  // namespace

std::string model_description_xml(const FmuInterface& fmu, const UnitSystem& units,
                                  const std::string& tool, const std::string& generated) {
  std::ostringstream xml;
  xml << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
      << "<fmiModelDescription fmiVersion=\"2.0\" modelName=\"" << escaped(fmu.model_name)
      << "\" guid=\"" << fmu.guid << "\" description=\"" << escaped(fmu.description)
      << "\" generationTool=\"" << escaped(tool) << "\" generationDateAndTime=\"" << generated
      << "\" variableNamingConvention=\"structured\" numberOfEventIndicators=\"0\">\n"
      << "  <CoSimulation modelIdentifier=\"" << fmu.model_identifier
      << "\" canHandleVariableCommunicationStepSize=\"true\" canInterpolateInputs=\"false\" "
         "maxOutputDerivativeOrder=\"0\" canRunAsynchronuously=\"false\" "
         "canBeInstantiatedOnlyOncePerProcess=\"false\" "
         "canNotUseMemoryManagementFunctions=\"true\" "
         "canGetAndSetFMUstate=\"false\" canSerializeFMUstate=\"false\" "
         "providesDirectionalDerivative=\"false\"/>\n";
  write_units(xml, fmu, units);
  xml << "  <DefaultExperiment startTime=\"0\" stopTime=\"" << real(fmu.stop_time)
      << "\" tolerance=\"" << real(fmu.tolerance) << "\"/>\n  <ModelVariables>\n";
  for (const auto& variable : fmu.variables) write_variable(xml, variable);
  xml << "  </ModelVariables>\n  <ModelStructure>\n    <Outputs>\n";
  std::ostringstream unknowns;
  for (std::size_t k = 0; k < fmu.variables.size(); ++k)
    if (fmu.variables[k].causality == FmuVariable::Causality::output)
      unknowns << "      <Unknown index=\"" << k + 1 << "\"/>\n";  // 1-based
  xml << unknowns.str() << "    </Outputs>\n    <InitialUnknowns>\n"
      << unknowns.str() << "    </InitialUnknowns>\n  </ModelStructure>\n"
      << "</fmiModelDescription>\n";
  return xml.str();
}

// ---- The standard's rules ---------------------------------------------------------------------

namespace {

struct DocumentDeleter {
  void operator()(xmlDoc* document) const { xmlFreeDoc(document); }
};

std::optional<std::string> attribute(const xmlNode* node, const char* name) {
  xmlChar* value = xmlGetProp(node, reinterpret_cast<const xmlChar*>(name));
  if (!value) return std::nullopt;
  std::string text(reinterpret_cast<const char*>(value));
  xmlFree(value);
  return text;
}

bool named(const xmlNode* node, const char* name) {
  return node->type == XML_ELEMENT_NODE &&
         xmlStrcmp(node->name, reinterpret_cast<const xmlChar*>(name)) == 0;
}

std::vector<const xmlNode*> children(const xmlNode* node, const char* name) {
  std::vector<const xmlNode*> found;
  for (const xmlNode* child = node ? node->children : nullptr; child; child = child->next)
    if (named(child, name)) found.push_back(child);
  return found;
}

std::optional<double> number(const std::optional<std::string>& text) {
  if (!text) return std::nullopt;
  try {
    std::size_t used = 0;
    const double value = std::stod(*text, &used);
    if (used == text->size()) return value;
  } catch (const std::exception&) {
  }
  return std::nullopt;
}

bool is_integer(const std::string& text) {
  std::size_t k = (!text.empty() && (text[0] == '+' || text[0] == '-')) ? 1 : 0;
  if (k == text.size()) return false;
  for (; k < text.size(); ++k)
    if (!std::isdigit(static_cast<unsigned char>(text[k]))) return false;
  return true;
}

std::optional<long> integer(const std::optional<std::string>& text) {
  if (!text || !is_integer(*text) || text->size() > 18) return std::nullopt;
  return std::stol(*text);
}

// A C identifier: a letter or underscore, then letters, digits, underscores. (Hand-written, as
// the names below: GCC 12 reports false uninitialised uses inside <regex> under ASan.)
bool c_identifier(std::string_view text) {
  if (text.empty() || std::isdigit(static_cast<unsigned char>(text[0]))) return false;
  for (const char c : text)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
  return true;
}

// FMI 2.0 section 2.2.9, variableNamingConvention="structured": identifiers (or 'quoted names')
// separated by dots, each optionally indexed [1,2], or der(name) and der(name, n).
bool structured_name(std::string_view name) {
  if (name.substr(0, 4) == "der(" && name.back() == ')') {
    std::string_view inner = name.substr(4, name.size() - 5);
    const auto comma = inner.rfind(',');
    if (comma != std::string_view::npos && is_integer(std::string(inner.substr(comma + 1))))
      inner = inner.substr(0, comma);
    return structured_name(inner);
  }
  std::size_t k = 0;
  while (true) {
    if (k < name.size() && name[k] == '\'') {  // a quoted name: no quote or backslash inside
      const auto end = name.find('\'', k + 1);
      if (end == std::string_view::npos ||
          name.substr(k + 1, end - k - 1).find('\\') != std::string_view::npos)
        return false;
      k = end + 1;
    } else {
      std::size_t end = k;
      while (end < name.size() && name[end] != '.' && name[end] != '[') ++end;
      if (!c_identifier(name.substr(k, end - k))) return false;
      k = end;
    }
    if (k < name.size() && name[k] == '[') {  // [1] or [1,2]
      const auto end = name.find(']', k);
      if (end == std::string_view::npos || end == k + 1) return false;
      for (std::size_t i = k + 1; i < end; ++i)
        if (!std::isdigit(static_cast<unsigned char>(name[i])) &&
            !(name[i] == ',' && i > k + 1 && i + 1 < end && name[i - 1] != ','))
          return false;
      k = end + 1;
    }
    if (k == name.size()) return true;
    if (name[k] != '.') return false;
    ++k;
  }
}

struct Checker {
  std::vector<std::string> problems;
  void fail(const std::string& problem) { problems.push_back(problem); }

  void root(const xmlNode* root) {
    if (!named(root, "fmiModelDescription")) return fail("the root is not fmiModelDescription");
    if (attribute(root, "fmiVersion") != "2.0") fail("fmiVersion: expected \"2.0\"");
    for (const char* required : {"modelName", "guid"})
      if (!attribute(root, required)) fail(std::string("fmiModelDescription: no ") + required);
    const auto convention = attribute(root, "variableNamingConvention");
    if (convention && *convention != "flat" && *convention != "structured")
      fail("variableNamingConvention: expected flat or structured, got " + *convention);
  }

  void co_simulation(const xmlNode* root) {
    const auto elements = children(root, "CoSimulation");
    if (elements.size() != 1) return fail("expected one CoSimulation element");
    const auto identifier = attribute(elements[0], "modelIdentifier");
    if (!identifier || !c_identifier(*identifier))
      fail("CoSimulation: modelIdentifier must be a C identifier");
  }

  std::set<std::string> units(const xmlNode* root) {
    std::set<std::string> names;
    for (const xmlNode* definitions : children(root, "UnitDefinitions")) {
      for (const xmlNode* unit : children(definitions, "Unit")) {
        const auto name = attribute(unit, "name");
        if (!name) {
          fail("Unit: no name");
          continue;
        }
        if (!names.insert(*name).second) fail("Unit " + *name + ": defined twice");
        for (const xmlNode* base : children(unit, "BaseUnit")) {
          for (const char* exponent : SiBaseUnit::kSymbols)
            if (attribute(base, exponent) && !integer(attribute(base, exponent)))
              fail("Unit " + *name + ": BaseUnit " + exponent + " must be an integer");
          for (const char* real_attribute : {"factor", "offset"})
            if (attribute(base, real_attribute) && !number(attribute(base, real_attribute)))
              fail("Unit " + *name + ": BaseUnit " + real_attribute + " must be a number");
        }
      }
    }
    return names;
  }

  // Section 2.2.7: the allowed combinations of causality and variability, and of initial.
  void combination(const std::string& where, const std::string& causality,
                   const std::string& variability, const std::optional<std::string>& initial,
                   bool has_start) {
    static const std::map<std::string, std::set<std::string>> kAllowed{
        {"parameter", {"fixed", "tunable"}},
        {"calculatedParameter", {"fixed", "tunable"}},
        {"input", {"discrete", "continuous"}},
        {"output", {"constant", "discrete", "continuous"}},
        {"local", {"constant", "fixed", "tunable", "discrete", "continuous"}},
        {"independent", {"continuous"}}};
    const auto allowed = kAllowed.find(causality);
    if (allowed == kAllowed.end()) return fail(where + ": unknown causality " + causality);
    if (!allowed->second.count(variability))
      return fail(where + ": causality " + causality + " with variability " + variability +
                  " is not allowed");
    std::string effective;  // the default initial of each combination
    std::set<std::string> permitted;
    if (causality == "input" || causality == "independent") {
      if (initial) fail(where + ": an " + causality + " has no initial attribute");
      if (causality == "input" && !has_start) fail(where + ": an input needs a start value");
      if (causality == "independent" && has_start)
        fail(where + ": the independent variable has no start value");
      return;
    }
    if (variability == "constant") {
      effective = "exact", permitted = {"exact"};
    } else if (causality == "parameter") {
      effective = "exact", permitted = {"exact"};
    } else if (causality == "calculatedParameter") {
      effective = "calculated", permitted = {"approx", "calculated"};
    } else {  // output or local, discrete or continuous
      effective = "calculated", permitted = {"exact", "approx", "calculated"};
    }
    const std::string used = initial.value_or(effective);
    if (!permitted.count(used))
      return fail(where + ": initial=\"" + used + "\" is not allowed for causality " + causality +
                  ", variability " + variability);
    if (used == "calculated" && has_start)
      fail(where + ": a calculated variable has no start value");
    if (used != "calculated" && !has_start)
      fail(where + ": initial=\"" + used + "\" needs a start value");
  }

  // The variables, 1-based, with their causality and initial.
  std::vector<std::pair<std::string, std::string>> variables(const xmlNode* root,
                                                             const std::set<std::string>& units) {
    std::vector<std::pair<std::string, std::string>> found;
    const auto lists = children(root, "ModelVariables");
    if (lists.size() != 1) {
      fail("expected one ModelVariables element");
      return found;
    }
    const bool structured = attribute(root, "variableNamingConvention") == "structured";
    std::set<std::string> names;
    std::map<std::string, std::set<long>> references;  // per base type
    for (const xmlNode* variable : children(lists[0], "ScalarVariable")) {
      const auto name = attribute(variable, "name");
      const std::string where = "ScalarVariable " + name.value_or("(no name)");
      if (!name) fail(where + ": no name");
      if (name && !names.insert(*name).second) fail(where + ": the name is used twice");
      if (name && structured && !structured_name(*name))
        fail(where + ": not a structured name (2.2.9)");
      std::string type;
      const xmlNode* element = nullptr;
      for (const xmlNode* child = variable->children; child; child = child->next) {
        if (child->type != XML_ELEMENT_NODE) continue;
        for (const char* candidate : {"Real", "Integer", "Boolean", "String", "Enumeration"})
          if (named(child, candidate)) {
            if (element) fail(where + ": more than one type element");
            element = child, type = candidate;
          }
      }
      if (!element) {
        fail(where + ": no type element (Real, Integer, Boolean, String, Enumeration)");
        found.emplace_back("", "");
        continue;
      }
      const auto reference = integer(attribute(variable, "valueReference"));
      if (!reference || *reference < 0)
        fail(where + ": valueReference must be a non-negative integer");
      else if (!references[type == "Enumeration" ? "Integer" : type].insert(*reference).second)
        fail(where + ": valueReference " + std::to_string(*reference) + " is used twice");
      const std::string causality = attribute(variable, "causality").value_or("local");
      const std::string variability = attribute(variable, "variability").value_or("continuous");
      if (variability == "continuous" && type != "Real")
        fail(where + ": only a Real can be continuous");
      const auto initial = attribute(variable, "initial");
      const auto start = attribute(element, "start");
      combination(where, causality, variability, initial, start.has_value());
      if (type == "Real") real_attributes(where, element, units);
      found.emplace_back(causality, initial.value_or(causality == "output" ? "calculated" : ""));
    }
    return found;
  }

  void real_attributes(const std::string& where, const xmlNode* element,
                       const std::set<std::string>& units) {
    const auto unit = attribute(element, "unit");
    if (unit && !units.count(*unit))
      fail(where + ": unit \"" + *unit + "\" is not in UnitDefinitions");
    std::map<std::string, double> values;
    for (const char* key : {"start", "min", "max", "nominal"}) {
      const auto text = attribute(element, key);
      if (!text) continue;
      const auto value = number(text);
      if (!value)
        fail(where + ": " + key + " is not a number");
      else
        values[key] = *value;
    }
    if (values.count("min") && values.count("max") && values["min"] > values["max"])
      fail(where + ": min is above max");
    if (values.count("start") && values.count("min") && values["start"] < values["min"])
      fail(where + ": start is below min");
    if (values.count("start") && values.count("max") && values["start"] > values["max"])
      fail(where + ": start is above max");
  }

  void structure(const xmlNode* root,
                 const std::vector<std::pair<std::string, std::string>>& variables) {
    const auto structures = children(root, "ModelStructure");
    if (structures.size() != 1) return fail("expected one ModelStructure element");
    std::vector<long> outputs, initial;
    for (std::size_t k = 0; k < variables.size(); ++k)
      if (variables[k].first == "output") outputs.push_back(static_cast<long>(k + 1));
    auto indices = [&](const char* list) {
      std::vector<long> listed;
      for (const xmlNode* element : children(structures[0], list))
        for (const xmlNode* unknown : children(element, "Unknown")) {
          const auto index = integer(attribute(unknown, "index"));
          if (!index || *index < 1 || *index > static_cast<long>(variables.size()))
            fail(std::string(list) + ": an Unknown's index is not a variable's (1-based)");
          else
            listed.push_back(*index);
        }
      return listed;
    };
    if (indices("Outputs") != outputs)
      fail("ModelStructure Outputs: expected exactly the outputs, in the order of ModelVariables");
    const auto listed = indices("InitialUnknowns");
    for (const long index : outputs) {
      const auto& initial_kind = variables[static_cast<std::size_t>(index - 1)].second;
      const bool needed = initial_kind == "calculated" || initial_kind == "approx";
      if (needed && std::find(listed.begin(), listed.end(), index) == listed.end())
        fail("ModelStructure InitialUnknowns: output " + std::to_string(index) +
             " is calculated and must be listed");
    }
  }

  void experiment(const xmlNode* root) {
    for (const xmlNode* element : children(root, "DefaultExperiment")) {
      const auto start = number(attribute(element, "startTime"));
      const auto stop = number(attribute(element, "stopTime"));
      if (start && stop && *start > *stop) fail("DefaultExperiment: startTime after stopTime");
    }
  }
};

}  // namespace

std::vector<std::string> model_description_problems(const std::string& xml) {
  std::unique_ptr<xmlDoc, DocumentDeleter> document(
      xmlReadMemory(xml.data(), static_cast<int>(xml.size()), "modelDescription.xml", nullptr,
                    XML_PARSE_NONET | XML_PARSE_NOERROR | XML_PARSE_NOWARNING));
  if (!document) return {"not well-formed XML"};
  Checker checker;
  const xmlNode* root = xmlDocGetRootElement(document.get());
  checker.root(root);
  if (!checker.problems.empty()) return checker.problems;
  checker.co_simulation(root);
  const auto units = checker.units(root);
  const auto variables = checker.variables(root, units);
  checker.structure(root, variables);
  checker.experiment(root);
  return checker.problems;
}

}  // namespace tcpmsim::fmu
