#include "analysis/spring_modes.h"

#include <Eigen/Eigenvalues>
#include <cmath>

namespace tcpmsim {

std::vector<double> clamped_eigenfrequencies(const CoilSpringChain& chain) {
  // M = (m/N) I, so the eigenproblem K v = w^2 M v is symmetric after dividing by m/N.
  const Eigen::MatrixXd stiffness = chain.stiffness_matrix();
  const double winding_mass = chain.defaults().mass / chain.defaults().windings;
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> solver(stiffness / winding_mass,
                                                        Eigen::EigenvaluesOnly);
  std::vector<double> frequencies;
  for (int i = 0; i < solver.eigenvalues().size(); ++i)
    frequencies.push_back(std::sqrt(solver.eigenvalues()(i)));
  return frequencies;
}

std::complex<double> force_transmissibility(const CoilSpringChain& chain, double omega) {
  // (K + i omega C - omega^2 M) X = k_0 e_0 U for a unit end motion U at the first end;
  // C = beta K with beta the chain's stiffness-proportional damping time.
  const int n = chain.defaults().windings;
  const double beta = chain.defaults().damping_time();
  const std::complex<double> element_factor(1.0, omega * beta);
  Eigen::MatrixXcd system = chain.stiffness_matrix().cast<std::complex<double>>() * element_factor -
                            chain.mass_matrix().cast<std::complex<double>>() * (omega * omega);
  Eigen::VectorXcd forcing = Eigen::VectorXcd::Zero(n);
  const std::complex<double> end_stiffness = chain.element_stiffness(0) * element_factor;
  forcing(0) = end_stiffness;
  const Eigen::VectorXcd motion = system.partialPivLu().solve(forcing);
  const std::complex<double> input_force =
      end_stiffness * (motion(0) - 1.0);  // T_0 = k_0 (xi_0 - u1)
  const std::complex<double> output_force =
      -chain.element_stiffness(n) * element_factor * motion(n - 1);
  return output_force / input_force;
}

double continuum_transmissibility(double omega, double mass, double stiffness) {
  return 1.0 /
         std::cos(omega * std::sqrt(mass / stiffness));  // (4.1): 2 / (e^{i w tau} + e^{-i w tau})
}

}  // namespace tcpmsim
