#include "sim/system.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

namespace tcpmsim {

namespace {
std::string qualified(const Component& component, const std::string& name) {
  return component.group() + "." + name;
}
}  // namespace

void System::connect(const Component& consumer, std::string_view input_name,
                     std::string_view source_output) {
  connections_.push_back({&consumer, std::string(input_name), std::string(source_output)});
}

int System::signal_index(std::string_view output) const {
  for (const auto& channel : channels_) {
    if (channel.group.size() + 1 + channel.name.size() == output.size() &&
        output.starts_with(channel.group) && output[channel.group.size()] == '.' &&
        output.ends_with(channel.name)) {
      return channel.signal_index;
    }
  }
  return -1;
}

void System::assemble() {
  states_.clear();
  channels_.clear();
  signal_owner_.clear();
  std::set<std::string> state_names;
  int signal_count = 0;
  for (std::size_t c = 0; c < components_.size(); ++c) {
    Component& component = *components_[c];
    component.state_offset_ = static_cast<int>(states_.size());
    for (const auto& declared : component.states()) {
      std::string name = qualified(component, declared.name);
      if (!state_names.insert(name).second) {
        throw std::logic_error("two components declare the state '" + name + "'");
      }
      states_.push_back({name, declared.unit, declared.absolute_tolerance, &component});
    }
    component.output_offset_ = signal_count;
    for (const auto& declared : component.outputs()) {
      if (signal_index(qualified(component, declared.name)) >= 0) {
        throw std::logic_error("two components publish the output '" +
                               qualified(component, declared.name) + "'");
      }
      channels_.push_back(
          {component.group(), declared.name, declared.unit, signal_count++, declared.observed});
      signal_owner_.push_back(static_cast<int>(c));
    }
    component.input_signal_index_.assign(component.inputs().size(), -1);
  }
  state_size_ = static_cast<int>(states_.size());
  signals_.assign(static_cast<std::size_t>(signal_count), 0.0);

  for (const auto& connection : connections_) {
    const auto declared = connection.consumer->inputs();
    auto input = std::find_if(declared.begin(), declared.end(),
                              [&](const auto& d) { return d.name == connection.input; });
    if (input == declared.end()) {
      throw std::logic_error(connection.consumer->group() + "/" + connection.consumer->kind() +
                             " has no input '" + connection.input + "'");
    }
    const int source = signal_index(connection.source);
    if (source < 0) {
      throw std::logic_error("no component publishes '" + connection.source + "' (needed by " +
                             connection.consumer->group() + "/" + connection.consumer->kind() +
                             ")");
    }
    if (channels_[static_cast<std::size_t>(source)].observed && !input->sampled) {
      throw std::logic_error("'" + connection.source +
                             "' is an observed output; only sampled inputs may read it (" +
                             connection.consumer->group() + "/" + connection.consumer->kind() +
                             " input '" + connection.input + "')");
    }
    auto& consumer = const_cast<Component&>(*connection.consumer);
    consumer.input_signal_index_[static_cast<std::size_t>(input - declared.begin())] = source;
  }
  for (const auto& component : components_) {
    const auto declared = component->inputs();
    for (std::size_t i = 0; i < declared.size(); ++i) {
      if (component->input_signal_index_[i] < 0) {
        throw std::logic_error(component->group() + "/" + component->kind() + " input '" +
                               declared[i].name + "' is not connected");
      }
    }
  }
  order_by_feedthrough();
  sampling_order_ = evaluation_order_;
  std::stable_sort(sampling_order_.begin(), sampling_order_.end(),
                   [](const Component* a, const Component* b) {
                     return a->sampling_stage() < b->sampling_stage();
                   });
  event_offsets_.clear();
  state_counts_.clear();
  event_count_ = 0;
  for (const auto& component : components_) {
    event_offsets_.push_back(event_count_);
    event_count_ += component->event_count();
    state_counts_.push_back(static_cast<int>(component->states().size()));
  }
  assembled_ = true;
}

void System::order_by_feedthrough() {
  const std::size_t count = components_.size();
  std::vector<std::set<std::size_t>> depends_on(count);
  for (std::size_t c = 0; c < count; ++c) {
    const auto declared = components_[c]->inputs();
    for (std::size_t i = 0; i < declared.size(); ++i) {
      if (!declared[i].direct_feedthrough) continue;
      const auto owner = static_cast<std::size_t>(
          signal_owner_[static_cast<std::size_t>(components_[c]->input_signal_index_[i])]);
      if (owner != c) depends_on[c].insert(owner);
    }
  }
  evaluation_order_.clear();
  std::vector<char> placed(count, 0);
  while (evaluation_order_.size() < count) {
    bool progress = false;
    for (std::size_t c = 0; c < count; ++c) {
      if (placed[c]) continue;
      const bool ready = std::all_of(depends_on[c].begin(), depends_on[c].end(),
                                     [&](std::size_t d) { return placed[d] != 0; });
      if (!ready) continue;
      placed[c] = 1;
      evaluation_order_.push_back(components_[c].get());
      progress = true;
    }
    if (!progress) {
      std::string members;
      for (std::size_t c = 0; c < count; ++c) {
        if (!placed[c]) members += " " + components_[c]->group() + "/" + components_[c]->kind();
      }
      throw std::logic_error("algebraic loop through direct-feedthrough inputs:" + members);
    }
  }
}

Evaluation System::evaluation(double time, double signal_time, const double* state) {
  return Evaluation{time, signal_time, state, signals_.data()};
}

void System::initialize(double time, double* state) {
  if (!assembled_) throw std::logic_error("System::initialize before assemble");
  std::fill(state, state + state_size_, 0.0);
  const Evaluation now = evaluation(time, time, state);
  for (Component* component : evaluation_order_) {
    const auto size = component->states().size();
    component->initialize(now, std::span<double>(state + component->state_offset_, size));
    component->compute_outputs(now);
  }
  evaluate_outputs(time, time, state);
}

void System::evaluate_outputs(double time, double signal_time, const double* state) {
  const Evaluation now = evaluation(time, signal_time, state);
  for (const Component* component : evaluation_order_) component->compute_outputs(now);
  for (const Component* component : evaluation_order_) component->compute_observations(now);
}

void System::evaluate_derivatives(double time, double signal_time, const double* state,
                                  double* derivatives) {
  const Evaluation now = evaluation(time, signal_time, state);
  for (const Component* component : evaluation_order_) component->compute_outputs(now);
  for (const Component* component : evaluation_order_) {
    component->compute_derivatives(now, derivatives);
  }
}

double System::next_breakpoint_after(double time) const {
  double next = kNoBreakpoint;
  for (const auto& component : components_) {
    next = std::min(next, component->next_breakpoint_after(time));
  }
  return next;
}

void System::at_breakpoint(double time, double left_limit, const double* state) {
  evaluate_outputs(time, left_limit, state);
  const Evaluation now = evaluation(time, left_limit, state);
  // Instruments first (a drive that measures as well as heats publishes its reading), then each
  // component republishes its outputs right after acting, so a controller sampling after an
  // estimator at the same instant sees the new estimate.
  for (Component* component : sampling_order_) {
    component->sense(now);
    component->compute_outputs(now);
    component->compute_observations(now);
  }
  for (Component* component : sampling_order_) {
    component->at_breakpoint(now);
    component->compute_outputs(now);
    component->compute_observations(now);
  }
  evaluate_outputs(time, left_limit, state);
}

void System::adapt_tolerances(double* absolute, double* relative) const {
  for (std::size_t c = 0; c < components_.size(); ++c) {
    const auto& component = components_[c];
    const auto size = static_cast<std::size_t>(state_counts_[c]);
    if (size == 0) continue;
    component->adapt_tolerances(std::span<double>(absolute + component->state_offset_, size),
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

void System::evaluate_events(double time, double signal_time, const double* state, double* values) {
  const Evaluation now = evaluation(time, signal_time, state);
  for (const Component* component : evaluation_order_) component->compute_outputs(now);
  for (std::size_t c = 0; c < components_.size(); ++c) {
    if (components_[c]->event_count() > 0)
      components_[c]->event_functions(now, values + event_offsets_[c]);
  }
}

void System::at_events(double time, double signal_time, const double* state, const int* flags) {
  evaluate_outputs(time, signal_time, state);
  const Evaluation now = evaluation(time, signal_time, state);
  for (std::size_t c = 0; c < components_.size(); ++c) {
    for (int k = 0; k < components_[c]->event_count(); ++k) {
      if (flags[event_offsets_[c] + k] != 0) components_[c]->at_event(k, now);
    }
  }
}

std::string System::check_component_contracts(double time, const double* state) {
  const double sentinel = -123456.789;
  std::vector<double> derivatives(static_cast<std::size_t>(state_size_));
  const Evaluation now = evaluation(time, time, state);
  for (std::size_t c = 0; c < components_.size(); ++c) {
    Component& component = *components_[c];
    const std::string name = component.group() + "/" + component.kind();
    const auto outputs = component.outputs().size();
    const auto begin = static_cast<std::size_t>(component.output_offset_);
    evaluate_outputs(time, time, state);  // inputs as they would be
    const std::vector<double> before = signals_;
    for (std::size_t i = begin; i < begin + outputs; ++i) signals_[i] = sentinel;
    component.compute_outputs(now);
    component.compute_observations(now);
    for (std::size_t i = 0; i < signals_.size(); ++i) {
      const bool own = i >= begin && i < begin + outputs;
      if (!own && signals_[i] != before[i] && !(std::isnan(signals_[i]) && std::isnan(before[i]))) {
        return name + " wrote signal " + std::to_string(i) + ", outside its outputs";
      }
      if (own && signals_[i] == sentinel)
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
  evaluate_outputs(time, time, state);
  return {};
}

SparsityPattern System::jacobian_pattern() const {
  // States each signal depends on, through chains of direct feedthrough.
  std::vector<std::vector<int>> signal_states(signals_.size());
  std::vector<char> resolved(signals_.size(), 0);
  auto resolve = [&](auto&& self, int signal) -> const std::vector<int>& {
    auto index = static_cast<std::size_t>(signal);
    if (resolved[index]) return signal_states[index];
    resolved[index] = 1;  // the feedthrough order guarantees no cycle
    const Component& owner = *components_[static_cast<std::size_t>(signal_owner_[index])];
    const auto deps = owner.output_dependencies(signal - owner.output_offset_);
    std::set<int> collected;
    for (int s : deps.states) collected.insert(owner.state_offset_ + s);
    for (int i : deps.inputs) {
      const auto& upstream = self(self, owner.input_signal_index_[static_cast<std::size_t>(i)]);
      collected.insert(upstream.begin(), upstream.end());
    }
    signal_states[index].assign(collected.begin(), collected.end());
    return signal_states[index];
  };

  SparsityPattern pattern;
  pattern.size = state_size_;
  pattern.rows_of_column.assign(static_cast<std::size_t>(state_size_), {});
  for (const auto& component : components_) {
    const int local_states = static_cast<int>(component->states().size());
    for (int s = 0; s < local_states; ++s) {
      const int row = component->state_offset_ + s;
      const auto deps = component->derivative_dependencies(s);
      std::set<int> columns;
      for (int d : deps.states) columns.insert(component->state_offset_ + d);
      for (int i : deps.inputs) {
        const auto& upstream =
            resolve(resolve, component->input_signal_index_[static_cast<std::size_t>(i)]);
        columns.insert(upstream.begin(), upstream.end());
      }
      columns.insert(row);  // the diagonal is always present in I - gamma J
      for (int column : columns)
        pattern.rows_of_column[static_cast<std::size_t>(column)].push_back(row);
    }
  }
  for (auto& rows : pattern.rows_of_column) std::sort(rows.begin(), rows.end());
  return pattern;
}

}  // namespace tcpmsim
