#pragma once

#include "sim/value_check.h"

// The ranges the muscles' and springs' parameters usually take (ValueCheck::typical): a value
// outside one is accepted with a located warning, because it is far more often a slipped unit
// (14.04 N/mm for mN/mm: 1000 times off) than a muscle of its own kind. Each range holds the
// thesis' values (Tables 6.4 and 7.2; the springs of chapters 2-4) and those the TCPM
// literature reports for nylon and polyethylene muscles from 0.1 to 2 mm fibres (Haines et al.
// 2014; Yip and Niemeyer 2017), with room on both sides; each is narrower than a factor of 1000
// around the thesis' value on at least one side, so that a slipped prefix leaves it. In SI.
namespace tcpmsim::typical {

// Mechanics of a muscle (SLS, (7.5)-(7.6)): the thesis' nylon muscle has k1 = 10.8 N/m.
inline ValueCheck stiffness(ValueCheck check) {
  return check.typical(0.1, 5000.0);
}  // N/m
inline ValueCheck added_stiffness(ValueCheck check) {
  return check.typical(0.0, 5000.0);
}  // k2
inline ValueCheck damping(ValueCheck check) {
  return check.typical(0.01, 5000.0);
}  // N*s/m
inline ValueCheck force_offset(ValueCheck check) {
  return check.typical(-5.0, 5.0);
}  // N

// The reduced thermal force (7.1): kappa_P = 7.2e-3 N/J, kappa_c = 0.1316 1/s in Table 7.2.
inline ValueCheck heating_gain(ValueCheck check) {
  return check.typical(1e-5, 1.0);
}  // N/J
inline ValueCheck cooling_rate(ValueCheck check) {
  return check.typical(1e-3, 10.0);
}  // 1/s
inline ValueCheck force_per_kelvin(ValueCheck check) {
  return check.typical(1e-5, 1.0);
}  // N/K

// The thermal node (6.5): C and hA of a muscle of 0.05 to 2 g; hA of still air to a fan.
inline ValueCheck heat_capacity(ValueCheck check) {
  return check.typical(1e-3, 50.0);
}  // J/K
inline ValueCheck conductance(ValueCheck check) {
  return check.typical(1e-5, 1.0);
}  // W/K
inline ValueCheck radiating_area(ValueCheck check) {
  return check.typical(1e-6, 0.1);
}  // m^2
// A temperature of a bench or a muscle (ambient, reference): -43 to 327 degC. A slip here is
// degC written as K.
inline ValueCheck temperature(ValueCheck check) {
  return check.typical(230.0, 600.0);
}  // K

// The heater and its supply: a constantan winding of 10.18 ohm (Table 7.1) at 7 V.
inline ValueCheck resistance(ValueCheck check) {
  return check.typical(0.01, 1000.0);
}  // ohm
inline ValueCheck supply_voltage(ValueCheck check) {
  return check.typical(0.1, 1000.0);
}  // V

// A load's mass: the ch. 6 iron muscle lifts 35 g.
inline ValueCheck mass(ValueCheck check) {
  return check.typical(1e-4, 100.0);
}  // kg
// A coil's geometry (chapters 2-4, and the muscles' coils).
inline ValueCheck coil_radius(ValueCheck check) {
  return check.typical(1e-5, 0.1);
}  // m
inline ValueCheck wire_diameter(ValueCheck check) {
  return check.typical(1e-6, 0.05);
}  // m

// What effects, bundles and joints add (models/effects, models/bundle, the antagonistic joint):
// sizes of the same muscles, each with zero allowed where zero switches the term off.
inline ValueCheck added_conductance(ValueCheck check) {
  return check.typical(0.0, 1.0);
}  // W/K: an extra heat loss, up to a fan's
inline ValueCheck time_constant(ValueCheck check) {
  return check.typical(0.01, 1e5);
}  // s: a relaxation, a lag or a spin-up, from the SLS's seconds to a day's warm-up
inline ValueCheck muscle_length(ValueCheck check) {
  return check.typical(1e-6, 1.0);
}  // m: a radius, a knee's width, a deflection along a muscle
inline ValueCheck effect_force(ValueCheck check) {
  return check.typical(0.0, 5.0);
}  // N: a friction's saturation, as the force offset
inline ValueCheck fibre_pitch(ValueCheck check) {
  return check.typical(1e-5, 0.1);
}  // m: the spacing of a bundle's muscles
inline ValueCheck joint_radius(ValueCheck check) {
  return check.typical(1e-4, 1.0);
}  // m: a pulley's radius (10 mm in configs/pair)
inline ValueCheck inertia(ValueCheck check) {
  return check.typical(1e-10, 10.0);
}  // kg*m^2: a joint's rotor

}  // namespace tcpmsim::typical
