#include "sim/system.h"

#include <algorithm>
#include <cmath>
#include <deque>
#include <set>
#include <stdexcept>
#include <unordered_set>

#include "sim/context.h"
#include "sim/signal.h"
#include "sim/value_check.h"

namespace tcpmsim {

namespace {
std::string qualified(const Component& component, const std::string& name) {
  return component.group() + "." + name;
}

std::string named(const Component& component) {
  return component.group() + "/" + component.kind();
}
}  // namespace

// ---------------------------------------------------------------------------------------------
// Building

void SystemBuilder::connect(const Component& consumer, std::string_view input_name,
                            std::string_view source_output) {
  connections_.push_back({&consumer, std::string(input_name), std::string(source_output), origin_});
}

void SystemBuilder::export_input(std::string_view port, const Component& consumer,
                                 std::string_view input_name) {
  if (!ports_.emplace(std::string(port), Export{&consumer, std::string(input_name)}).second)
    throw std::logic_error("two inputs are exported as the port '" + std::string(port) + "'");
}

void SystemBuilder::share_input(std::string_view port, const Component& consumer,
                                std::string_view input_name) {
  shared_ports_.emplace(std::string(port), Export{&consumer, std::string(input_name)});
}

void SystemBuilder::connect(std::string_view port, std::string_view source_output) {
  port_connections_.push_back({std::string(port), std::string(source_output), origin_});
}

bool SystemBuilder::is_connected(std::string_view port) const {
  for (const auto& connection : port_connections_) {
    if (connection.port == port) return true;
  }
  return false;
}

int SystemBuilder::origin_of(const Component& component) const {
  const auto found = component_origins_.find(&component);
  return found == component_origins_.end() ? -1 : found->second;
}

void SystemBuilder::derive(std::string path, ParameterRule rule, std::string explanation) {
  derivations_.push_back({std::move(path), std::move(rule), std::move(explanation)});
}

void SystemBuilder::constrain(ParameterConstraint constraint) {
  constraints_.push_back(std::move(constraint));
}

bool SystemBuilder::declares_parameter(std::string_view path) const {
  for (const auto& component : components_) {
    for (const auto& declared : component->parameters())
      if (declared.path == path) return true;
  }
  return false;
}

void SystemBuilder::declare_members(MemberSet set) {
  member_sets_.push_back(std::move(set));
}

std::shared_ptr<const System> SystemBuilder::build() {
  std::shared_ptr<System> system(new System());
  system->components_ = std::move(components_);
  system->member_sets_ = std::move(member_sets_);
  system->assign_slices(*this);
  system->wire(*this);
  system->order_by_feedthrough(*this);
  system->collect_parameters(*this);
  *this = SystemBuilder();
  return system;
}

// ---------------------------------------------------------------------------------------------
// Assembly

void System::assign_slices(const SystemBuilder& builder) {
  std::unordered_set<std::string> state_names;
  std::unordered_set<std::string> parameter_paths;
  for (std::size_t c = 0; c < components_.size(); ++c) {
    Component& component = *components_[c];
    component.index_ = static_cast<int>(c);
    component.state_offset_ = static_cast<int>(states_.size());
    for (const auto& declared : component.states()) {
      std::string name = qualified(component, declared.name);
      if (!state_names.insert(name).second) {
        throw AssemblyError("two components declare the state '" + name + "'",
                            {builder.origin_of(component)});
      }
      states_.push_back({std::move(name), declared.unit, declared.absolute_tolerance, &component});
    }
    state_counts_.push_back(static_cast<int>(states_.size()) - component.state_offset_);
    component.output_offset_ = static_cast<int>(channels_.size());
    for (const auto& declared : component.outputs()) {
      const std::string name = qualified(component, declared.name);
      if (!channel_by_name_.emplace(name, static_cast<int>(channels_.size())).second) {
        throw AssemblyError("two components publish the output '" + name + "'",
                            {builder.origin_of(component)});
      }
      channels_.push_back({component.group(), declared.name, declared.unit,
                           static_cast<int>(channels_.size()), declared.observed,
                           declared.recorded});
      signal_owner_.push_back(static_cast<int>(c));
    }
    inputs_.push_back(component.inputs());
    component.parameter_offset_ = static_cast<int>(parameters_.size());
    for (auto& declared : component.parameters()) parameters_.push_back({std::move(declared), {}});
    parameter_counts_.push_back(static_cast<int>(parameters_.size()) - component.parameter_offset_);
    const auto external = component.external_inputs();
    for (std::size_t e = 0; e < external.size(); ++e) {
      external_inputs_.push_back({qualified(component, external[e].name), external[e].unit,
                                  &component, static_cast<int>(e)});
    }
    component.signal_offset_ = static_cast<int>(signal_slots_.size());
    for (const auto& declared : component.signals()) {
      SignalSlot slot{component.group(),
                      declared.name,
                      declared.unit,
                      declared.signal,
                      static_cast<int>(parameters_.size()),
                      0};
      for (auto& parameter : declared.signal->parameters())
        parameters_.push_back({std::move(parameter), {}});
      slot.parameter_count = static_cast<int>(parameters_.size()) - slot.first_parameter;
      const std::string name = qualified(component, declared.name);
      if (!slot_by_name_.emplace(name, static_cast<int>(signal_slots_.size())).second)
        throw AssemblyError("a component declares the signal '" + name + "' twice",
                            {builder.origin_of(component)});
      signal_slots_.push_back(std::move(slot));
    }
  }
  for (std::size_t p = 0; p < parameters_.size(); ++p) {
    const std::string& path = parameters_[p].declaration.path;
    if (!parameter_by_path_.emplace(path, static_cast<int>(p)).second)
      throw AssemblyError("two components declare the parameter '" + path + "'", {});
  }
}

void System::wire(const SystemBuilder& builder) {
  // Sources per component and input, in connection order, with the origin of each connection.
  struct Source {
    int signal;
    int origin;
  };
  std::vector<std::vector<std::vector<Source>>> sources(components_.size());
  for (std::size_t c = 0; c < components_.size(); ++c) sources[c].resize(inputs_[c].size());
  auto attach = [&](const Component& consumer, const std::string& input_name,
                    const std::string& source, int origin) {
    const auto c = static_cast<std::size_t>(consumer.index_);
    const auto& declared = inputs_[c];
    const auto input = std::find_if(declared.begin(), declared.end(),
                                    [&](const auto& d) { return d.name == input_name; });
    if (input == declared.end())
      throw AssemblyError(named(consumer) + " has no input '" + input_name + "'", {origin});
    const int index = signal_index(source);
    if (index < 0) {
      throw AssemblyError(
          "no component publishes '" + source + "' (needed by " + named(consumer) + ")", {origin});
    }
    if (channels_[static_cast<std::size_t>(index)].observed && !input->sampled) {
      throw AssemblyError("'" + source +
                              "' is an observed output; only sampled inputs may read it (" +
                              named(consumer) + " input '" + input_name + "')",
                          {origin});
    }
    sources[c][static_cast<std::size_t>(input - declared.begin())].push_back({index, origin});
  };
  for (const auto& connection : builder.connections_)
    attach(*connection.consumer, connection.input, connection.source, connection.origin);
  for (const auto& connection : builder.port_connections_) {
    const auto exported = builder.ports_.find(connection.port);
    if (exported == builder.ports_.end())
      throw AssemblyError(
          "no input port '" + connection.port + "' (to connect to '" + connection.source + "')",
          {connection.origin});
    attach(*exported->second.consumer, exported->second.input, connection.source,
           connection.origin);
    const auto [first, last] = builder.shared_ports_.equal_range(connection.port);
    for (auto sharer = first; sharer != last; ++sharer)
      attach(*sharer->second.consumer, sharer->second.input, connection.source, connection.origin);
  }
  for (std::size_t c = 0; c < components_.size(); ++c) {
    Component& component = *components_[c];
    const auto& declared = inputs_[c];
    component.first_source_.assign(declared.size(), -1);
    component.fan_in_begin_.clear();
    component.fan_in_count_.clear();
    component.fan_in_sources_.clear();
    for (std::size_t i = 0; i < declared.size(); ++i) {
      const auto& wired = sources[c][i];
      const auto count = wired.size();
      if (count == 0 && declared[i].arity == InputArity::one) {
        throw AssemblyError(named(component) + " input '" + declared[i].name + "' is not connected",
                            {builder.origin_of(component)});
      }
      if (count > 1 && declared[i].arity != InputArity::many) {
        // Reported at the connection that came last, naming every one's origin.
        std::vector<int> origins{wired.back().origin};
        for (const auto& source : wired) origins.push_back(source.origin);
        throw AssemblyError(named(component) + " input '" + declared[i].name +
                                "' takes one source, but " + std::to_string(count) +
                                " are connected",
                            origins);
      }
      if (count > 0) component.first_source_[i] = wired.front().signal;
      component.fan_in_begin_.push_back(static_cast<int>(component.fan_in_sources_.size()));
      component.fan_in_count_.push_back(static_cast<int>(count));
      for (const auto& source : wired) component.fan_in_sources_.push_back(source.signal);
    }
    if (std::string problem = component.check_connections(); !problem.empty())
      throw AssemblyError(named(component) + " " + problem, {builder.origin_of(component)});
  }
}

void System::order_by_feedthrough(const SystemBuilder& builder) {
  // Kahn's algorithm over "reads through direct feedthrough" edges, first-come first-placed.
  const std::size_t count = components_.size();
  std::vector<std::vector<std::size_t>> readers(count);
  std::vector<int> waiting(count, 0);
  for (std::size_t c = 0; c < count; ++c) {
    const Component& component = *components_[c];
    std::set<std::size_t> owners;
    for (std::size_t i = 0; i < inputs_[c].size(); ++i) {
      if (!inputs_[c][i].direct_feedthrough) continue;
      const int begin = component.fan_in_begin_[i];
      for (int k = 0; k < component.fan_in_count_[i]; ++k) {
        const auto owner = static_cast<std::size_t>(signal_owner_[static_cast<std::size_t>(
            component.fan_in_sources_[static_cast<std::size_t>(begin + k)])]);
        if (owner != c) owners.insert(owner);
      }
    }
    waiting[c] = static_cast<int>(owners.size());
    for (std::size_t owner : owners) readers[owner].push_back(c);
  }
  std::deque<std::size_t> ready;
  for (std::size_t c = 0; c < count; ++c) {
    if (waiting[c] == 0) ready.push_back(c);
  }
  evaluation_order_.clear();
  while (!ready.empty()) {
    const std::size_t c = ready.front();
    ready.pop_front();
    evaluation_order_.push_back(components_[c].get());
    for (std::size_t reader : readers[c]) {
      if (--waiting[reader] == 0) ready.push_back(reader);
    }
  }
  if (evaluation_order_.size() < count) {
    std::string members;
    std::vector<int> origins;
    for (std::size_t c = 0; c < count; ++c) {
      if (waiting[c] == 0) continue;
      members += ' ';  // appended piecewise: GCC 12 warns falsely (-Wrestrict) on " " + s
      members += named(*components_[c]);
      origins.push_back(builder.origin_of(*components_[c]));
    }
    throw AssemblyError("algebraic loop through direct-feedthrough inputs:" + members, origins);
  }
  sampling_order_ = evaluation_order_;
  std::stable_sort(sampling_order_.begin(), sampling_order_.end(),
                   [](const Component* a, const Component* b) {
                     return a->sampling_stage() < b->sampling_stage();
                   });
  for (const auto& component : components_) {
    event_offsets_.push_back(event_count_);
    event_count_ += component->event_count();
  }
}

void System::collect_parameters(const SystemBuilder& builder) {
  for (const auto& pending : builder.derivations_) {
    const auto index = parameter_index(pending.path);
    if (!index) throw std::logic_error("no parameter '" + pending.path + "' to derive");
    // One rule per parameter: a second would silently replace the first.
    if (!parameters_[static_cast<std::size_t>(*index)].derived_from.empty())
      throw std::logic_error("two rules derive the parameter '" + pending.path + "'");
    parameters_[static_cast<std::size_t>(*index)].derived_from = pending.explanation;
    derivations_.push_back({*index, pending.rule});
  }
  constraints_ = builder.constraints_;
}

// ---------------------------------------------------------------------------------------------
// Queries

int System::signal_index(std::string_view output) const {
  const auto found = channel_by_name_.find(std::string(output));
  if (found == channel_by_name_.end()) return -1;
  return channels_[static_cast<std::size_t>(found->second)].signal_index;
}

std::optional<int> System::parameter_index(std::string_view path) const {
  const auto found = parameter_by_path_.find(std::string(path));
  if (found == parameter_by_path_.end()) return std::nullopt;
  return found->second;
}

std::optional<int> System::signal_slot(std::string_view group, std::string_view name) const {
  std::string key(group);
  key += '.';
  key += name;
  const auto found = slot_by_name_.find(key);
  if (found == slot_by_name_.end()) return std::nullopt;
  return found->second;
}

// ---------------------------------------------------------------------------------------------
// Runs

Evaluation System::evaluation(Context& context, double time, double signal_time,
                              const double* state) const {
  return Evaluation{time,
                    signal_time,
                    state,
                    context.signals_.data(),
                    context.parameters_.data(),
                    context.run_states_.data(),
                    context.prescribed_.data()};
}

RunSetup System::setup_of(const Context& context, std::size_t component) const {
  return {std::span<const double>(context.parameters_)
              .subspan(static_cast<std::size_t>(components_[component]->parameter_offset_),
                       static_cast<std::size_t>(parameter_counts_[component])),
          context};
}

void System::rebuild_signals(Context& context) const {
  // Signals whose parameters the context changed are made again with the new values.
  for (std::size_t s = 0; s < signal_slots_.size(); ++s) {
    const SignalSlot& slot = signal_slots_[s];
    const auto first = static_cast<std::size_t>(slot.first_parameter);
    const auto count = static_cast<std::size_t>(slot.parameter_count);
    bool changed = false;
    for (std::size_t p = first; p < first + count; ++p)
      changed = changed || context.parameters_[p] != parameters_[p].declaration.value;
    context.rebuilt_signals_[s].reset();
    context.prescribed_[s] = slot.signal;
    if (!changed) continue;
    try {
      context.rebuilt_signals_[s] = slot.signal->with_parameters(
          std::span<const double>(context.parameters_).subspan(first, count));
    } catch (const std::exception& error) {
      throw ParameterError(slot.group + "." + slot.name, error.what());
    }
    context.prescribed_[s] = context.rebuilt_signals_[s].get();
  }
}

void System::check_run_parameters(const Context& context) const {
  for (std::size_t c = 0; c < components_.size(); ++c) {
    if (std::string problem = components_[c]->check_parameters(setup_of(context, c));
        !problem.empty())
      throw ParameterError(named(*components_[c]), problem);
  }
  for (const auto& constraint : constraints_) {
    if (std::string problem = constraint(context); !problem.empty())
      throw ParameterError("", problem);
  }
}

void System::prepare(Context& context) const {
  if (context.system_ != this) throw std::logic_error("the context belongs to another system");
  context.prepared_ = false;
  rebuild_signals(context);
  for (const auto& derivation : derivations_) {
    const auto index = static_cast<std::size_t>(derivation.parameter);
    const double value = derivation.rule(context);
    // A derived value meets its declared range like any other.
    if (std::string problem = parameter_problem(parameters_[index].declaration, value);
        !problem.empty())
      throw ParameterError(parameters_[index].declaration.path,
                           problem + " (derived: " + parameters_[index].derived_from + ")");
    context.parameters_[index] = value;
  }
  // The values the model was built with passed these checks when it was read.
  if (context.parameters_changed()) check_run_parameters(context);
  for (std::size_t c = 0; c < components_.size(); ++c) {
    context.run_states_[c] = components_[c]->create_run_state(setup_of(context, c));
    context.prepared_ = true;
  }
}

void System::initialize(Context& context, double time, double* state) const {
  if (!context.prepared_) prepare(context);
  context.prepared_ = false;  // this run uses the run states up: the next one starts afresh
  std::fill(state, state + state_size(), 0.0);
  const Evaluation now = evaluation(context, time, time, state);
  for (int round = 0; round < 2; ++round) {
    for (const Component* component : evaluation_order_) {
      const auto size =
          static_cast<std::size_t>(state_counts_[static_cast<std::size_t>(component->index_)]);
      component->initialize(now, std::span<double>(state + component->state_offset_, size));
      component->compute_outputs(now);
    }
  }
  evaluate_outputs(context, time, time, state);
}

void System::evaluate_outputs(Context& context, double time, double signal_time,
                              const double* state) const {
  const Evaluation now = evaluation(context, time, signal_time, state);
  for (const Component* component : evaluation_order_) component->compute_outputs(now);
  for (const Component* component : evaluation_order_) component->compute_observations(now);
}

void System::evaluate_derivatives(Context& context, double time, double signal_time,
                                  const double* state, double* derivatives) const {
  const Evaluation now = evaluation(context, time, signal_time, state);
  for (const Component* component : evaluation_order_) component->compute_outputs(now);
  for (const Component* component : evaluation_order_) {
    component->compute_derivatives(now, derivatives);
  }
}

double System::next_breakpoint_after(Context& context, double time) const {
  const Evaluation now = evaluation(context, time, time, nullptr);
  double next = kNoBreakpoint;
  for (const auto& component : components_) {
    next = std::min(next, component->next_breakpoint_after(now));
  }
  return next;
}

void System::at_breakpoint(Context& context, double time, double left_limit,
                           const double* state) const {
  begin_instant(context, time, left_limit, state);
  end_instant(context, time, left_limit, state);
}

namespace {
bool acts_before_controllers(const Component& component) {
  return component.sampling_stage() < Component::SamplingStage::controller;
}
}  // namespace

void System::begin_instant(Context& context, double time, double left_limit,
                           const double* state) const {
  evaluate_outputs(context, time, left_limit, state);
  const Evaluation now = evaluation(context, time, left_limit, state);
  // Instruments first (a drive that measures as well as heats publishes its reading), then each
  // component republishes its outputs right after acting, so a controller sampling after an
  // estimator at the same instant sees the new estimate.
  for (const Component* component : sampling_order_) {
    component->sense(now);
    component->compute_outputs(now);
    component->compute_observations(now);
  }
  for (const Component* component : sampling_order_) {
    if (!acts_before_controllers(*component)) break;  // sorted by stage
    component->at_breakpoint(now);
    component->compute_outputs(now);
    component->compute_observations(now);
  }
}

void System::end_instant(Context& context, double time, double left_limit,
                         const double* state) const {
  const Evaluation now = evaluation(context, time, left_limit, state);
  for (const Component* component : sampling_order_) {
    if (acts_before_controllers(*component)) continue;
    component->at_breakpoint(now);
    component->compute_outputs(now);
    component->compute_observations(now);
  }
  evaluate_outputs(context, time, left_limit, state);
}

std::pair<double, double> System::external_input_range(Context& context, int input) const {
  const ExternalInputInfo& info = external_inputs_.at(static_cast<std::size_t>(input));
  return info.owner->external_input_range(evaluation(context, 0.0, 0.0, nullptr), info.index);
}

void System::hold_external_input(Context& context, int input, double value) const {
  const ExternalInputInfo& info = external_inputs_.at(static_cast<std::size_t>(input));
  const auto [lower, upper] = external_input_range(context, input);
  if (!(value >= lower && value <= upper)) {
    throw std::invalid_argument(info.name + ": " + number_text(value) + " " + info.unit +
                                " is outside its range [" + number_text(lower) + ", " +
                                number_text(upper) + "] " + info.unit);
  }
  info.owner->hold_external_input(evaluation(context, 0.0, 0.0, nullptr), info.index, value);
}

void System::adapt_tolerances(Context& context, double* absolute, double* relative) const {
  const Evaluation now = evaluation(context, 0.0, 0.0, nullptr);
  for (std::size_t c = 0; c < components_.size(); ++c) {
    const auto& component = components_[c];
    const auto size = static_cast<std::size_t>(state_counts_[c]);
    if (size == 0) continue;
    component->adapt_tolerances(now, std::span<double>(absolute + component->state_offset_, size),
                                std::span<double>(relative + component->state_offset_, size));
  }
}

std::vector<int> System::event_directions() const {
  std::vector<int> directions;
  for (const auto& component : components_) {
    for (int k = 0; k < component->event_count(); ++k)
      directions.push_back(component->event_direction(k));
  }
  return directions;
}

void System::evaluate_events(Context& context, double time, double signal_time, const double* state,
                             double* values) const {
  const Evaluation now = evaluation(context, time, signal_time, state);
  for (const Component* component : evaluation_order_) component->compute_outputs(now);
  for (std::size_t c = 0; c < components_.size(); ++c) {
    if (components_[c]->event_count() > 0)
      components_[c]->event_functions(now, values + event_offsets_[c]);
  }
}

void System::at_events(Context& context, double time, double signal_time, const double* state,
                       const int* flags) const {
  evaluate_outputs(context, time, signal_time, state);
  const Evaluation now = evaluation(context, time, signal_time, state);
  for (std::size_t c = 0; c < components_.size(); ++c) {
    for (int k = 0; k < components_[c]->event_count(); ++k) {
      if (flags[event_offsets_[c] + k] != 0) components_[c]->at_event(k, now);
    }
  }
}

std::string System::check_component_contracts(Context& context, double time,
                                              const double* state) const {
  const double sentinel = -123456.789;
  std::vector<double>& signals = context.signals_;
  std::vector<double> derivatives(static_cast<std::size_t>(state_size()));
  const Evaluation now = evaluation(context, time, time, state);
  for (std::size_t c = 0; c < components_.size(); ++c) {
    const Component& component = *components_[c];
    const std::string name = named(component);
    const auto outputs = component.outputs().size();
    const auto begin = static_cast<std::size_t>(component.output_offset_);
    evaluate_outputs(context, time, time, state);  // inputs as they would be
    const std::vector<double> before = signals;
    for (std::size_t i = begin; i < begin + outputs; ++i) signals[i] = sentinel;
    component.compute_outputs(now);
    component.compute_observations(now);
    for (std::size_t i = 0; i < signals.size(); ++i) {
      const bool own = i >= begin && i < begin + outputs;
      if (!own && signals[i] != before[i] && !(std::isnan(signals[i]) && std::isnan(before[i]))) {
        return name + " wrote signal " + std::to_string(i) + ", outside its outputs";
      }
      if (own && signals[i] == sentinel)
        return name + " did not write its output " + std::to_string(i - begin);
    }
    std::fill(derivatives.begin(), derivatives.end(), sentinel);
    component.compute_derivatives(now, derivatives.data());
    const auto first = static_cast<std::size_t>(component.state_offset_);
    const auto count = static_cast<std::size_t>(state_counts_[c]);
    for (std::size_t i = 0; i < derivatives.size(); ++i) {
      const bool own = i >= first && i < first + count;
      if (!own && derivatives[i] != sentinel)
        return name + " wrote derivative " + std::to_string(i) + ", not its own";
      if (own && derivatives[i] == sentinel)
        return name + " did not write its derivative " + std::to_string(i - first);
    }
  }
  evaluate_outputs(context, time, time, state);
  return {};
}

const ChannelInfo* System::source_of(const Component& consumer, std::string_view input) const {
  for (std::size_t c = 0; c < components_.size(); ++c) {
    if (components_[c].get() != &consumer) continue;
    for (std::size_t i = 0; i < inputs_[c].size(); ++i) {
      if (inputs_[c][i].name != input) continue;
      const int signal = consumer.first_source_[i];
      return signal < 0 ? nullptr : &channels_[static_cast<std::size_t>(signal)];
    }
  }
  return nullptr;
}

bool System::reads_input(std::size_t component, int input, JacobianEntries entries) const {
  return entries == JacobianEntries::all ||
         !inputs_[component][static_cast<std::size_t>(input)].between_members;
}

std::vector<std::vector<int>> System::signal_state_dependencies(JacobianEntries entries) const {
  // States each signal depends on, through chains of direct feedthrough.
  std::vector<std::vector<int>> signal_states(channels_.size());
  std::vector<char> resolved(channels_.size(), 0);
  auto resolve = [&](auto&& self, int signal) -> const std::vector<int>& {
    auto index = static_cast<std::size_t>(signal);
    if (resolved[index]) return signal_states[index];
    resolved[index] = 1;  // the feedthrough order guarantees no cycle
    const Component& owner = *components_[static_cast<std::size_t>(signal_owner_[index])];
    const auto deps = owner.output_dependencies(signal - owner.output_offset_);
    std::set<int> collected;
    for (int s : deps.states) collected.insert(owner.state_offset_ + s);
    for (int i : deps.inputs) {
      if (!reads_input(static_cast<std::size_t>(signal_owner_[index]), i, entries)) continue;
      const auto input = static_cast<std::size_t>(i);
      for (int k = 0; k < owner.fan_in_count_[input]; ++k) {
        const auto& upstream = self(
            self, owner.fan_in_sources_[static_cast<std::size_t>(owner.fan_in_begin_[input] + k)]);
        collected.insert(upstream.begin(), upstream.end());
      }
    }
    signal_states[index].assign(collected.begin(), collected.end());
    return signal_states[index];
  };
  for (std::size_t signal = 0; signal < channels_.size(); ++signal)
    resolve(resolve, static_cast<int>(signal));
  return signal_states;
}

// The states derivative `s` of `component` reads, except through the input `skipped` (-1: none).
std::set<int> System::derivative_columns(const std::vector<std::vector<int>>& signal_states,
                                         std::size_t c, int s, int skipped,
                                         JacobianEntries entries) const {
  const Component& component = *components_[c];
  const auto deps = component.derivative_dependencies(s);
  std::set<int> columns;
  for (int d : deps.states) columns.insert(component.state_offset_ + d);
  for (int i : deps.inputs) {
    if (i == skipped || !reads_input(c, i, entries)) continue;
    const auto input = static_cast<std::size_t>(i);
    for (int k = 0; k < component.fan_in_count_[input]; ++k) {
      const auto& upstream = signal_states[static_cast<std::size_t>(
          component.fan_in_sources_[static_cast<std::size_t>(component.fan_in_begin_[input] + k)])];
      columns.insert(upstream.begin(), upstream.end());
    }
  }
  columns.insert(component.state_offset_ + s);  // the diagonal is always present in I - gamma J
  return columns;
}

SparsityPattern System::jacobian_pattern(JacobianEntries entries) const {
  const auto signal_states = signal_state_dependencies(entries);
  SparsityPattern pattern;
  pattern.size = state_size();
  pattern.rows_of_column.assign(static_cast<std::size_t>(state_size()), {});
  for (std::size_t c = 0; c < components_.size(); ++c) {
    for (int s = 0; s < state_counts_[c]; ++s) {
      const int row = components_[c]->state_offset_ + s;
      for (int column : derivative_columns(signal_states, c, s, -1, entries))
        pattern.rows_of_column[static_cast<std::size_t>(column)].push_back(row);
    }
  }
  for (auto& rows : pattern.rows_of_column) std::sort(rows.begin(), rows.end());
  return pattern;
}

std::vector<FanInRow> System::fan_in_rows(int min_sources) const {
  const auto signal_states = signal_state_dependencies();
  std::vector<FanInRow> rows;
  for (std::size_t c = 0; c < components_.size(); ++c) {
    const Component& component = *components_[c];
    for (int s = 0; s < state_counts_[c]; ++s) {
      for (int i : component.derivative_dependencies(s).inputs) {
        const auto input = static_cast<std::size_t>(i);
        if (component.fan_in_count_[input] < min_sources) continue;
        FanInRow row{component.state_offset_ + s, static_cast<int>(c), {}, {}, {}};
        for (int k = 0; k < component.fan_in_count_[input]; ++k) {
          const int signal =
              component
                  .fan_in_sources_[static_cast<std::size_t>(component.fan_in_begin_[input] + k)];
          row.sources.push_back(signal);
          row.source_states.push_back(signal_states[static_cast<std::size_t>(signal)]);
        }
        const auto direct = derivative_columns(signal_states, c, s, i);
        row.direct_states.assign(direct.begin(), direct.end());
        rows.push_back(std::move(row));
        break;  // one fan-in per row: a second one stays in the ordinary pattern
      }
    }
  }
  return rows;
}

double System::row_sensitivity(Context& context, double time, double signal_time,
                               const double* state, const FanInRow& row, int signal, double step,
                               double* scratch) const {
  const Evaluation now = evaluation(context, time, signal_time, state);
  const Component& owner = *components_[static_cast<std::size_t>(row.component)];
  double& value = now.signals[signal];
  const double original = value;
  value = original + step;
  owner.compute_outputs(now);
  owner.compute_derivatives(now, scratch);
  const double raised = scratch[row.row];
  value = original - step;
  owner.compute_outputs(now);
  owner.compute_derivatives(now, scratch);
  const double lowered = scratch[row.row];
  value = original;
  owner.compute_outputs(now);  // its outputs as they were
  return (raised - lowered) / (2.0 * step);
}

}  // namespace tcpmsim
