// The FMU of `tcpmsim export-fmu`, tested as an importer uses it: the archive unzipped, the
// description read, the library loaded with dlopen and driven through the FMI 2.0 functions
// (fmi2Instantiate ... fmi2DoStep ... fmi2Terminate) with inputs from a file; its outputs
// against `tcpmsim run` on the same inputs, and every bad use a master can make.
#include <dlfcn.h>
#include <libxml/parser.h>
#include <libxml/tree.h>
#include <zip.h>
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "analysis/record_channels.h"
#include "fmu/fmi2/fmi2FunctionTypes.h"
#include "fmu/model_description.h"

namespace fs = std::filesystem;

namespace {

std::string source(const std::string& path) {
  return std::string(TCPMSIM_SOURCE_DIR) + "/" + path;
}

fs::path scratch(const std::string& name) {
  const fs::path directory =
      fs::temp_directory_path() / "tcpmsim_tests" / ("fmu_" + std::to_string(::getpid())) / name;
  fs::remove_all(directory);
  fs::create_directories(directory);
  return directory;
}

int run_program(const std::string& arguments) {
  const std::string command = std::string(TCPMSIM_PROGRAM) + " " + arguments + " > /dev/null";
  return std::system(command.c_str());
}

void unzip(const fs::path& archive, const fs::path& into) {
  int error = 0;
  zip_t* zip = zip_open(archive.c_str(), ZIP_RDONLY, &error);
  REQUIRE(zip);
  for (zip_int64_t k = 0; k < zip_get_num_entries(zip, 0); ++k) {
    const std::string name = zip_get_name(zip, static_cast<zip_uint64_t>(k), 0);
    const fs::path target = into / name;
    fs::create_directories(target.parent_path());
    zip_file_t* file = zip_fopen_index(zip, static_cast<zip_uint64_t>(k), 0);
    REQUIRE(file);
    std::ofstream out(target, std::ios::binary);
    char buffer[65536];
    zip_int64_t read = 0;
    while ((read = zip_fread(file, buffer, sizeof buffer)) > 0) out.write(buffer, read);
    zip_fclose(file);
  }
  zip_close(zip);
}

std::string file_text(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// What an importer reads of modelDescription.xml: the identity and each variable's reference.
struct Description {
  std::string guid, identifier;
  std::map<std::string, fmi2ValueReference> references;
  std::map<std::string, std::map<std::string, std::string>> real;  // name -> Real's attributes
};

Description read_description(const std::string& xml) {
  Description description;
  xmlDoc* document = xmlReadMemory(xml.data(), static_cast<int>(xml.size()), "md.xml", nullptr, 0);
  REQUIRE(document);
  auto text = [](const xmlNode* node, const char* name) {
    xmlChar* value = xmlGetProp(node, reinterpret_cast<const xmlChar*>(name));
    std::string result = value ? reinterpret_cast<const char*>(value) : "";
    xmlFree(value);
    return result;
  };
  const xmlNode* root = xmlDocGetRootElement(document);
  description.guid = text(root, "guid");
  for (const xmlNode* node = root->children; node; node = node->next) {
    if (node->type != XML_ELEMENT_NODE) continue;
    const std::string element = reinterpret_cast<const char*>(node->name);
    if (element == "CoSimulation") description.identifier = text(node, "modelIdentifier");
    if (element != "ModelVariables") continue;
    for (const xmlNode* variable = node->children; variable; variable = variable->next) {
      if (variable->type != XML_ELEMENT_NODE) continue;
      const std::string name = text(variable, "name");
      description.references[name] =
          static_cast<fmi2ValueReference>(std::stoul(text(variable, "valueReference")));
      for (const xmlNode* type = variable->children; type; type = type->next)
        if (type->type == XML_ELEMENT_NODE)
          for (const xmlAttr* a = type->properties; a; a = a->next)
            description.real[name][reinterpret_cast<const char*>(a->name)] =
                text(type, reinterpret_cast<const char*>(a->name));
    }
  }
  xmlFreeDoc(document);
  return description;
}

// The log of every instance: what the FMU said through the master's logger.
std::vector<std::string>& messages() {
  static std::vector<std::string> logged;
  return logged;
}
void logger(fmi2ComponentEnvironment, fmi2String, fmi2Status status, fmi2String category,
            fmi2String format, ...) {
  char text[4096];
  va_list arguments;
  va_start(arguments, format);
  std::vsnprintf(text, sizeof text, format, arguments);
  va_end(arguments);
  messages().push_back(std::string(category) + " (" + std::to_string(status) + "): " + text);
}
bool logged(const std::string& part) {
  for (const auto& message : messages())
    if (message.find(part) != std::string::npos) return true;
  return false;
}
const fmi2CallbackFunctions kCallbacks{logger, nullptr, nullptr, nullptr, nullptr};

// The FMU unpacked and its library loaded, as an importer (FMPy, Simulink) does it.
struct LoadedFmu {
  fs::path root;
  Description description;
  void* library = nullptr;
  fmi2InstantiateTYPE* instantiate = nullptr;
  fmi2FreeInstanceTYPE* free_instance = nullptr;
  fmi2SetupExperimentTYPE* setup = nullptr;
  fmi2EnterInitializationModeTYPE* enter = nullptr;
  fmi2ExitInitializationModeTYPE* exit = nullptr;
  fmi2TerminateTYPE* terminate = nullptr;
  fmi2ResetTYPE* reset = nullptr;
  fmi2GetRealTYPE* get_real = nullptr;
  fmi2SetRealTYPE* set_real = nullptr;
  fmi2DoStepTYPE* do_step = nullptr;
  fmi2GetFMUstateTYPE* get_state = nullptr;

  explicit LoadedFmu(const fs::path& fmu) : root(fmu.parent_path() / "unpacked") {
    fs::remove_all(root);
    unzip(fmu, root);
    description = read_description(file_text(root / "modelDescription.xml"));
    const fs::path so = root / "binaries" / "linux64" / (description.identifier + ".so");
    library = dlopen(so.c_str(), RTLD_NOW | RTLD_LOCAL);
    INFO((library ? "" : dlerror()));
    REQUIRE(library);
    load(instantiate, "fmi2Instantiate");
    load(free_instance, "fmi2FreeInstance");
    load(setup, "fmi2SetupExperiment");
    load(enter, "fmi2EnterInitializationMode");
    load(exit, "fmi2ExitInitializationMode");
    load(terminate, "fmi2Terminate");
    load(reset, "fmi2Reset");
    load(get_real, "fmi2GetReal");
    load(set_real, "fmi2SetReal");
    load(do_step, "fmi2DoStep");
    load(get_state, "fmi2GetFMUstate");
  }
  ~LoadedFmu() {
    if (library) dlclose(library);
  }
  template <typename F>
  void load(F*& function, const char* name) {
    function = reinterpret_cast<F*>(dlsym(library, name));
    INFO(name);
    REQUIRE(function);
  }
  std::string resources() const { return "file://" + (root / "resources").string(); }
  fmi2Component instance(const std::string& guid = "") const {
    return instantiate("muscle", fmi2CoSimulation, (guid.empty() ? description.guid : guid).c_str(),
                       resources().c_str(), &kCallbacks, fmi2False, fmi2False);
  }
  fmi2ValueReference reference(const std::string& name) const {
    INFO(name);
    REQUIRE(description.references.count(name));
    return description.references.at(name);
  }
  double get(fmi2Component c, const std::string& name) const {
    const fmi2ValueReference vr = reference(name);
    double value = 0.0;
    REQUIRE(get_real(c, &vr, 1, &value) == fmi2OK);
    return value;
  }
  fmi2Status set(fmi2Component c, const std::string& name, double value) const {
    const fmi2ValueReference vr = reference(name);
    return set_real(c, &vr, 1, &value);
  }
};

const char* kOutputs = "muscle.force,muscle.temperature,estimator.force,controller.reference";

// One FMU of the chapter-7 force bench, exported once for the tests.
const fs::path& force_fmu() {
  static const fs::path fmu = [] {
    const fs::path directory = scratch("force");
    const fs::path path = directory / "muscle.fmu";
    REQUIRE(run_program("export-fmu " + source("configs/ch7_control/external_force.yaml") + " -o " +
                        path.string() + " --outputs " + kOutputs) == 0);
    return path;
  }();
  return fmu;
}

}  // namespace

TEST_CASE("An exported FMU's description keeps FMI 2.0's rules, with SI units and start values") {
  LoadedFmu fmu(force_fmu());
  const std::string xml = file_text(fmu.root / "modelDescription.xml");
  CHECK(tcpmsim::fmu::model_description_problems(xml).empty());
  CHECK(fmu.description.identifier == "ch7_external_force");
  // The input: the Muscle Drive's power, held from P_min, within the PID's limits (7.9).
  const auto& power = fmu.description.real.at("controller.power_command");
  CHECK(power.at("unit") == "W");
  CHECK(std::stod(power.at("start")) == 0.10);
  CHECK(std::stod(power.at("min")) == 0.10);
  CHECK(std::stod(power.at("max")) == 3.12);
  // The outputs asked for, calculated (no start); the parameters with their scenario values.
  CHECK(fmu.description.real.at("muscle.force").count("start") == 0);
  CHECK(std::stod(fmu.description.real.at("parameters.muscle.thermal_force.kappa_P").at("start")) ==
        7.2e-3);
  CHECK(xml.find("<Unit name=\"W\"><BaseUnit kg=\"1\" m=\"2\" s=\"-3\"/></Unit>") !=
        std::string::npos);
  CHECK(xml.find("<Unit name=\"N/m\"><BaseUnit kg=\"1\" s=\"-2\"/></Unit>") != std::string::npos);
  CHECK(fs::exists(fmu.root / "resources" / "scenario.yaml"));
}

TEST_CASE("Every shipped scenario with an external input exports with all its outputs") {
  for (const std::string config : {"external_force", "external_deflection"}) {
    const fs::path path = scratch("all_" + config) / "all.fmu";
    REQUIRE(run_program("export-fmu " + source("configs/ch7_control/" + config + ".yaml") + " -o " +
                        path.string()) == 0);
    LoadedFmu fmu(path);
    const std::string xml = file_text(fmu.root / "modelDescription.xml");
    INFO(config);
    CHECK(tcpmsim::fmu::model_description_problems(xml).empty());
    // The recorded outputs but the input's own, and the parameters beside them by name.
    CHECK(fmu.description.references.count("muscle.force"));
    CHECK(fmu.description.references.count("muscle.resistance"));
    CHECK(fmu.description.references.count("parameters.muscle.resistance"));
    CHECK(fmu.description.references.count("controller.power_command"));
    CHECK(std::count(xml.begin(), xml.end(), '\n') > 100);
  }
  // A scenario without an external input has nothing for a master to set.
  CHECK(run_program("export-fmu " + source("configs/ch7_control/force_steps.yaml") + " -o " +
                    (scratch("none") / "x.fmu").string() + " 2> /dev/null") != 0);
  CHECK_FALSE(fs::exists(scratch("none") / "x.fmu"));
}

TEST_CASE(
    "The FMU's path is checked before any work: its directories are made, a directory is "
    "refused") {
  const fs::path nested = scratch("nested") / "new" / "deeper" / "muscle.fmu";
  CHECK(run_program("export-fmu " + source("configs/ch7_control/external_force.yaml") + " -o " +
                    nested.string()) == 0);
  CHECK(fs::is_regular_file(nested));
  // Exit code 4 (output), with the reason, and no scratch directory left beside it.
  const fs::path directory = scratch("a_directory");
  const fs::path message = scratch("message") / "message.txt";
  const int status = run_program("export-fmu " + source("configs/ch7_control/external_force.yaml") +
                                 " -o " + directory.string() + " 2> " + message.string());
  CHECK(WEXITSTATUS(status) == 4);
  CHECK(file_text(message).find("it is a directory") != std::string::npos);
  CHECK(std::distance(fs::directory_iterator(directory), fs::directory_iterator()) == 0);
}

TEST_CASE("The rules checker finds what breaks FMI 2.0 in a description") {
  LoadedFmu fmu(force_fmu());
  const std::string xml = file_text(fmu.root / "modelDescription.xml");
  auto problems_after = [&](const std::string& from, const std::string& to) {
    std::string broken = xml;
    const auto at = broken.find(from);
    REQUIRE(at != std::string::npos);
    broken.replace(at, from.size(), to);
    const auto problems = tcpmsim::fmu::model_description_problems(broken);
    std::string all;
    for (const auto& problem : problems) all += problem + "\n";
    return all;
  };
  CHECK_THAT(problems_after("fmiVersion=\"2.0\"", "fmiVersion=\"3.0\""),
             Catch::Contains("fmiVersion"));
  CHECK_THAT(problems_after("name=\"muscle.temperature\"", "name=\"muscle.force\""),
             Catch::Contains("the name is used twice"));
  CHECK_THAT(problems_after("valueReference=\"2\"", "valueReference=\"1\""),
             Catch::Contains("valueReference 1 is used twice"));
  CHECK_THAT(problems_after("<Real unit=\"N\"/>", "<Real unit=\"N\" start=\"0\"/>"),
             Catch::Contains("a calculated variable has no start value"));
  CHECK_THAT(problems_after("start=\"0.10000000000000001\" min", "min"),
             Catch::Contains("an input needs a start value"));
  CHECK_THAT(problems_after("causality=\"input\" variability=\"continuous\"",
                            "causality=\"input\" variability=\"fixed\""),
             Catch::Contains("causality input with variability fixed is not allowed"));
  CHECK_THAT(problems_after("<Real unit=\"W\"", "<Real unit=\"kW\""),
             Catch::Contains("unit \"kW\" is not in UnitDefinitions"));
  CHECK_THAT(problems_after("<Unknown index=\"3\"/>", ""),
             Catch::Contains("ModelStructure Outputs: expected exactly the outputs"));
  CHECK_THAT(problems_after("max=\"3.1200000000000001\"", "max=\"0.05\""),
             Catch::Contains("min is above max"));
  CHECK_THAT(problems_after("name=\"muscle.force\"", "name=\"muscle force\""),
             Catch::Contains("not a structured name"));
  // Structured names (2.2.9): dotted identifiers or 'quoted names', indices, der(...).
  for (const std::string good : {"muscle.force[1,2]", "der(muscle.force)", "der(muscle.x,2)",
                                 "'muscle force'.value", "_a.b3"})
    CHECK_THAT(problems_after("name=\"muscle.force\"", "name=\"" + good + "\""),
               !Catch::Contains("not a structured name"));
  for (const std::string bad : {"muscle..force", "muscle.force[]", "muscle.force[1,]", "3d.x",
                                "muscle.", "der(muscle force)"})
    CHECK_THAT(problems_after("name=\"muscle.force\"", "name=\"" + bad + "\""),
               Catch::Contains("not a structured name"));
  CHECK_THAT(problems_after("modelIdentifier=\"ch7_external_force\"", "modelIdentifier=\"7-x\""),
             Catch::Contains("modelIdentifier must be a C identifier"));
  CHECK(tcpmsim::fmu::model_description_problems("<fmiModelDescription") ==
        std::vector<std::string>{"not well-formed XML"});
}

// How many units in the last place separate a and b (NaN against NaN: none).
double ulps_apart(double a, double b) {
  if (std::isnan(a) && std::isnan(b)) return 0.0;
  if (a == b) return 0.0;
  return std::abs(a - b) / (std::nextafter(std::abs(b), INFINITY) - std::abs(b));
}

TEST_CASE("Driven with inputs from a file, the FMU reproduces tcpmsim run's record") {
  // The inputs: the power the built-in PID commanded in force_steps.yaml (the same plant,
  // drive, estimator, task and seed as the FMU's scenario), from tcpmsim run's record, written
  // to a CSV file as a master's input table.
  const fs::path directory = scratch("replay");
  REQUIRE(run_program("run " + source("configs/ch7_control/force_steps.yaml") + " -q -o " +
                      (directory / "pid.h5").string()) == 0);
  const auto record = tcpmsim::read_record_channels((directory / "pid.h5").string());
  {
    std::ofstream inputs(directory / "inputs.csv");
    inputs.precision(17);
    inputs << "time,controller.power_command\n";
    const auto& power = record.channel("controller/power_command").values;
    for (std::size_t k = 0; k < record.time.size(); ++k)
      inputs << record.time[k] << "," << power[k] << "\n";
  }

  // The master: read the table; at each point read the outputs, set the input, step 50 ms (the
  // drive's PWM period, the PID's sampling).
  LoadedFmu fmu(force_fmu());
  std::vector<std::pair<double, double>> table;
  {
    std::ifstream inputs(directory / "inputs.csv");
    std::string line;
    std::getline(inputs, line);
    while (std::getline(inputs, line)) {
      const auto comma = line.find(',');
      table.emplace_back(std::stod(line.substr(0, comma)), std::stod(line.substr(comma + 1)));
    }
  }
  REQUIRE(table.size() == 3601);
  messages().clear();
  fmi2Component c = fmu.instance();
  REQUIRE(c);
  REQUIRE(fmu.setup(c, fmi2True, 1e-5, 0.0, fmi2True, 180.0) == fmi2OK);
  REQUIRE(fmu.enter(c) == fmi2OK);
  REQUIRE(fmu.exit(c) == fmi2OK);
  std::map<std::string, std::vector<double>> outputs;
  for (std::size_t k = 0; k < table.size(); ++k) {
    for (const std::string name :
         {"muscle.force", "muscle.temperature", "estimator.force", "controller.reference"})
      outputs[name].push_back(fmu.get(c, name));
    if (k + 1 == table.size()) break;
    REQUIRE(fmu.set(c, "controller.power_command", table[k].second) == fmi2OK);
    REQUIRE(fmu.do_step(c, table[k].first, 0.05, fmi2True) == fmi2OK);
  }
  REQUIRE(fmu.terminate(c) == fmi2OK);
  fmu.free_instance(c);
  CHECK(messages().empty());

  // The sampled quantities a controller reads (the estimate, the reference) are the record's
  // bit for bit at every point. The plant's continuous outputs are too, to rounding: the master
  // reads CVODE's solution at the step's end, the record interpolates it at the output time
  // (CVodeGetDky, a sum over its Nordsieck history), and the two differ by a few ulps (4 here).
  for (const auto& [name, values] : outputs) {
    std::string channel = name;
    channel[channel.find('.')] = '/';
    const auto& expected = record.channel(channel).values;
    INFO(name);
    REQUIRE(values.size() == expected.size());
    const bool sampled = name == "estimator.force" || name == "controller.reference";
    double worst = 0.0;
    for (std::size_t k = 0; k < values.size(); ++k)
      worst = std::max(worst, ulps_apart(values[k], expected[k]));
    CHECK(worst <= (sampled ? 0.0 : 8.0));
  }
}

TEST_CASE("Every bad use of the FMU returns fmi2Error with a logged message, never a crash") {
  LoadedFmu fmu(force_fmu());
  messages().clear();
  SECTION("instantiation: another GUID, model exchange, no scenario in the resources") {
    CHECK(fmu.instance("{00000000-0000-0000-0000-000000000000}") == nullptr);
    CHECK(logged("is not this FMU's"));
    CHECK(fmu.instantiate("m", fmi2ModelExchange, fmu.description.guid.c_str(),
                          fmu.resources().c_str(), &kCallbacks, fmi2False, fmi2False) == nullptr);
    CHECK(logged("co-simulation only"));
    const fs::path empty = scratch("no_resources");
    CHECK(fmu.instantiate("m", fmi2CoSimulation, fmu.description.guid.c_str(),
                          ("file://" + empty.string()).c_str(), &kCallbacks, fmi2False,
                          fmi2False) == nullptr);
    CHECK(logged("the FMU's resources have no"));
    CHECK(fmu.instantiate("m", fmi2CoSimulation, fmu.description.guid.c_str(), "http://x/y",
                          &kCallbacks, fmi2False, fmi2False) == nullptr);
    CHECK(logged("is not a file URI"));
  }
  SECTION("a null instance") {
    CHECK(fmu.do_step(nullptr, 0.0, 0.05, fmi2True) == fmi2Error);
    CHECK(fmu.terminate(nullptr) == fmi2Error);
  }
  SECTION("calls out of their mode, values out of range, steps backwards") {
    fmi2Component c = fmu.instance();
    REQUIRE(c);
    CHECK(fmu.do_step(c, 0.0, 0.05, fmi2True) == fmi2Error);  // before initialization
    CHECK(logged("fmi2DoStep: not allowed when the instance is instantiated"));
    CHECK(fmu.setup(c, fmi2False, 0.0, 1.0, fmi2False, 0.0) == fmi2Error);
    CHECK(logged("a tcpmsim scenario starts at t = 0"));
    CHECK(fmu.setup(c, fmi2False, 0.0, 0.0, fmi2True, 1e4) == fmi2Error);
    CHECK(logged("after the scenario's end"));
    REQUIRE(fmu.setup(c, fmi2False, 0.0, 0.0, fmi2True, 10.0) == fmi2OK);
    REQUIRE(fmu.enter(c) == fmi2OK);
    // A parameter set in initialization is the run's: kappa_P doubled.
    CHECK(fmu.set(c, "parameters.muscle.thermal_force.kappa_P", 14.4e-3) == fmi2OK);
    CHECK(fmu.get(c, "parameters.muscle.thermal_force.kappa_P") == 14.4e-3);
    CHECK(fmu.set(c, "parameters.muscle.mechanics.k1", -1.0) == fmi2Error);
    CHECK(logged("parameters.muscle.mechanics.k1"));
    REQUIRE(fmu.exit(c) == fmi2OK);
    CHECK(fmu.get(c, "parameters.muscle.thermal_force.kappa_P") == 14.4e-3);
    CHECK(fmu.set(c, "parameters.muscle.thermal_force.kappa_P", 7.2e-3) == fmi2Error);
    CHECK(logged("is a fixed parameter"));

    CHECK(fmu.set(c, "controller.power_command", 4.0) == fmi2Error);
    CHECK(logged("outside its range"));
    CHECK(fmu.set(c, "muscle.force", 1.0) == fmi2Error);
    CHECK(logged("muscle.force is an output"));
    const fmi2ValueReference unknown = 9999;
    double value = 0.0;
    CHECK(fmu.get_real(c, &unknown, 1, &value) == fmi2Error);
    CHECK(fmu.set_real(c, &unknown, 1, &value) == fmi2Error);
    CHECK(logged("no variable has value reference 9999"));
    CHECK(fmu.get_real(c, nullptr, 1, nullptr) == fmi2Error);

    REQUIRE(fmu.set(c, "controller.power_command", 2.0) == fmi2OK);
    REQUIRE(fmu.do_step(c, 0.0, 0.5, fmi2True) == fmi2OK);
    CHECK(fmu.do_step(c, 0.25, 0.25, fmi2True) == fmi2Error);  // backwards
    CHECK(logged("is not the instance's time"));
    CHECK(fmu.do_step(c, 0.5, -0.1, fmi2True) == fmi2Error);
    CHECK(logged("expected a positive step"));
    CHECK(fmu.do_step(c, 0.5, 20.0, fmi2True) == fmi2Error);  // past stopTime
    CHECK(logged("passes the stop time"));
    fmi2FMUstate state = nullptr;
    CHECK(fmu.get_state(c, &state) == fmi2Error);
    CHECK(logged("fmi2GetFMUstate: not offered"));
    // After every refusal the instance goes on where it was.
    CHECK(fmu.do_step(c, 0.5, 0.5, fmi2True) == fmi2OK);
    CHECK(fmu.get(c, "muscle.temperature") > 296.15);
    REQUIRE(fmu.terminate(c) == fmi2OK);
    CHECK(fmu.do_step(c, 1.0, 0.05, fmi2True) == fmi2Error);
    CHECK(logged("when the instance is terminated"));
    // fmi2Reset: as instantiated, the parameters set since forgotten.
    REQUIRE(fmu.reset(c) == fmi2OK);
    CHECK(fmu.get(c, "parameters.muscle.thermal_force.kappa_P") == 7.2e-3);
    fmu.free_instance(c);
  }
  for (const auto& message : messages()) INFO(message);
  for (const auto& message : messages()) CHECK(message.rfind("logError (3): ", 0) == 0);
}
