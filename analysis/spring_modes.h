#pragma once

#include <complex>
#include <vector>

#include "models/coil_spring_chain.h"

namespace tcpmsim {

// The lumped-mass spring as a linear system, for checks against the continuum (thesis 4.2.1).

// Undamped clamped eigenfrequencies [rad/s], lowest first; the continuum's are n pi sqrt(k/m)
// (4.3).
std::vector<double> clamped_eigenfrequencies(const CoilSpringChain& chain);

// Steady-state force transmissibility F_o / F_i at angular frequency omega, with the first end
// driven harmonically and the second clamped; the continuum's is 1 / cos(omega tau),
// tau = sqrt(m/k) (4.1)-(4.2).
std::complex<double> force_transmissibility(const CoilSpringChain& chain, double omega);
double continuum_transmissibility(double omega, double mass, double stiffness);

}  // namespace tcpmsim
