// The optimised serial vector kernels compute exactly what Debian's SUNDIALS computes.
#include <catch2/catch.hpp>

#include <nvector/nvector_serial.h>
#include <sundials/sundials_context.h>

#include <cstring>
#include <vector>

#include "sim/random_stream.h"
#include "sim/serial_vector_kernels.h"

using namespace tcpmsim;

namespace {

// Two vector families over the same data: Debian's operations and ours.
struct Vectors {
  explicit Vectors(int size) {
    SUNContext_Create(nullptr, &context);
    reference = N_VNew_Serial(size, context);
    N_VEnableFusedOps_Serial(reference, SUNTRUE);
    optimised = N_VNew_Serial(size, context);
    install_optimised_serial_kernels(optimised);
  }
  ~Vectors() {
    for (N_Vector v : {reference, optimised}) N_VDestroy(v);
    SUNContext_Free(&context);
  }
  SUNContext context = nullptr;
  N_Vector reference = nullptr, optimised = nullptr;
};

struct Family {
  N_Vector make(double scale) {
    N_Vector v = N_VClone(prototype);
    for (sunindextype i = 0; i < NV_LENGTH_S(v); ++i)
      NV_Ith_S(v, i) = stream.uniform(-scale, scale);
    owned.push_back(v);
    return v;
  }
  ~Family() {
    for (N_Vector v : owned) N_VDestroy(v);
  }
  N_Vector prototype;
  RandomStream stream;
  std::vector<N_Vector> owned{};
};

bool same_bits(N_Vector a, N_Vector b) {
  return std::memcmp(NV_DATA_S(a), NV_DATA_S(b),
                     sizeof(double) * static_cast<std::size_t>(NV_LENGTH_S(a))) == 0;
}

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

}  // namespace

TEST_CASE("Optimised serial kernels are bit-identical to Debian's SUNDIALS kernels") {
  Vectors vectors(37);
  Family debian{vectors.reference, RandomStream(9, "kernels")};
  Family ours{vectors.optimised, RandomStream(9, "kernels")};  // same numbers
  const double coefficients[][2] = {{1, 1},     {1, -1},     {-1, 1},    {-1, -1},
                                    {0.3, 0.3}, {0.3, -0.3}, {1, 0.7},   {0.7, 1},
                                    {-1, 0.7},  {0.7, -1},   {0.3, 0.7}, {0, 0.5}};
  for (const auto& ab : coefficients) {
    INFO("a = " << ab[0] << ", b = " << ab[1]);
    N_Vector x1 = debian.make(3), y1 = debian.make(2), z1 = debian.make(1);
    N_Vector x2 = ours.make(3), y2 = ours.make(2), z2 = ours.make(1);
    N_VLinearSum(ab[0], x1, ab[1], y1, z1);
    N_VLinearSum(ab[0], x2, ab[1], y2, z2);
    CHECK(same_bits(z1, z2));
    N_VLinearSum(ab[0], x1, ab[1], y1, y1);  // in place, as CVODE's axpy use
    N_VLinearSum(ab[0], x2, ab[1], y2, y2);
    CHECK(same_bits(y1, y2));
    N_VLinearSum(ab[0], x1, ab[1], y1, x1);
    N_VLinearSum(ab[0], x2, ab[1], y2, x2);
    CHECK(same_bits(x1, x2));
  }
  N_Vector x1 = debian.make(5), w1 = debian.make(1), z1 = debian.make(1);
  N_Vector x2 = ours.make(5), w2 = ours.make(1), z2 = ours.make(1);
  CHECK(same_bits(N_VWrmsNorm(x1, w1), N_VWrmsNorm(x2, w2)));
  CHECK(same_bits(N_VWSqrSumLocal(x1, w1), N_VWSqrSumLocal(x2, w2)));
  CHECK(same_bits(N_VMaxNorm(x1), N_VMaxNorm(x2)));
  for (double c : {1.0, -1.0, 0.25}) {
    N_VScale(c, x1, z1), N_VScale(c, x2, z2);
    CHECK(same_bits(z1, z2));
  }
  N_VProd(x1, w1, z1), N_VProd(x2, w2, z2);
  CHECK(same_bits(z1, z2));
  N_VDiv(x1, w1, z1), N_VDiv(x2, w2, z2);
  CHECK(same_bits(z1, z2));
  N_VAbs(x1, z1), N_VAbs(x2, z2);
  CHECK(same_bits(z1, z2));
  N_VInv(x1, z1), N_VInv(x2, z2);
  CHECK(same_bits(z1, z2));
  N_VAddConst(x1, 0.125, z1), N_VAddConst(x2, 0.125, z2);
  CHECK(same_bits(z1, z2));
  N_VCompare(2.0, x1, z1), N_VCompare(2.0, x2, z2);
  CHECK(same_bits(z1, z2));
  N_VConst(0.5, z1), N_VConst(0.5, z2);
  CHECK(same_bits(z1, z2));

  for (int count : {1, 2, 3, 6}) {
    INFO(count << " vectors");
    std::vector<double> c{1.0, -0.5, 0.25, 2.0, 1.0 / 3.0, -1.0};
    std::vector<N_Vector> X1, X2, Z1, Z2;
    for (int k = 0; k < count; ++k) {
      X1.push_back(debian.make(1)), X2.push_back(ours.make(1));
      Z1.push_back(debian.make(1)), Z2.push_back(ours.make(1));
    }
    N_Vector s1 = debian.make(1), s2 = ours.make(1);
    N_VLinearCombination(count, c.data(), X1.data(), s1),
        N_VLinearCombination(count, c.data(), X2.data(), s2);
    CHECK(same_bits(s1, s2));
    N_VLinearCombination(count, c.data(), X1.data(), X1[0]),
        N_VLinearCombination(count, c.data(), X2.data(), X2[0]);
    CHECK(same_bits(X1[0], X2[0]));
    N_VScaleAddMulti(count, c.data(), s1, X1.data(), Z1.data()),
        N_VScaleAddMulti(count, c.data(), s2, X2.data(), Z2.data());
    for (int k = 0; k < count; ++k)
      CHECK(same_bits(Z1[static_cast<std::size_t>(k)], Z2[static_cast<std::size_t>(k)]));
    N_VScaleAddMulti(count, c.data(), s1, X1.data(), X1.data()),
        N_VScaleAddMulti(count, c.data(), s2, X2.data(), X2.data());
    for (int k = 0; k < count; ++k)
      CHECK(same_bits(X1[static_cast<std::size_t>(k)], X2[static_cast<std::size_t>(k)]));
  }
}
