#include "sim/serial_vector_kernels.h"

#include <nvector/nvector_serial.h>

#include <cmath>

namespace tcpmsim {

namespace {

struct View {
  explicit View(N_Vector v) : data(NV_DATA_S(v)), size(NV_LENGTH_S(v)) {}
  double* data;
  sunindextype size;
};

void linear_sum(double a, N_Vector x, double b, N_Vector y, N_Vector z) {
  const View xv(x), yv(y), zv(z);
  const double *xd = xv.data, *yd = yv.data;
  double* zd = zv.data;
  const sunindextype n = xv.size;
  if (a == b) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * (xd[i] + yd[i]);
  } else if (a == -b) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * (xd[i] - yd[i]);
  } else {
    for (sunindextype i = 0; i < n; ++i) zd[i] = (a * xd[i]) + (b * yd[i]);
  }
}

void constant(double c, N_Vector z) {
  const View zv(z);
  for (sunindextype i = 0; i < zv.size; ++i) zv.data[i] = c;
}

void product(N_Vector x, N_Vector y, N_Vector z) {
  const View xv(x), yv(y), zv(z);
  for (sunindextype i = 0; i < xv.size; ++i) zv.data[i] = xv.data[i] * yv.data[i];
}

void quotient(N_Vector x, N_Vector y, N_Vector z) {
  const View xv(x), yv(y), zv(z);
  for (sunindextype i = 0; i < xv.size; ++i) zv.data[i] = xv.data[i] / yv.data[i];
}

void scale(double c, N_Vector x, N_Vector z) {
  const View xv(x), zv(z);
  for (sunindextype i = 0; i < xv.size; ++i) zv.data[i] = c * xv.data[i];
}

void absolute(N_Vector x, N_Vector z) {
  const View xv(x), zv(z);
  for (sunindextype i = 0; i < xv.size; ++i) zv.data[i] = std::abs(xv.data[i]);
}

void inverse(N_Vector x, N_Vector z) {
  const View xv(x), zv(z);
  for (sunindextype i = 0; i < xv.size; ++i) zv.data[i] = 1.0 / xv.data[i];
}

void add_constant(N_Vector x, double b, N_Vector z) {
  const View xv(x), zv(z);
  for (sunindextype i = 0; i < xv.size; ++i) zv.data[i] = xv.data[i] + b;
}

double max_norm(N_Vector x) {
  const View xv(x);
  double largest = 0.0;
  for (sunindextype i = 0; i < xv.size; ++i) {
    if (std::abs(xv.data[i]) > largest) largest = std::abs(xv.data[i]);
  }
  return largest;
}

double weighted_square_sum(N_Vector x, N_Vector w) {
  const View xv(x), wv(w);
  double sum = 0.0;
  for (sunindextype i = 0; i < xv.size; ++i) {
    const double product = xv.data[i] * wv.data[i];
    sum += product * product;
  }
  return sum;
}

double weighted_rms_norm(N_Vector x, N_Vector w) {
  return std::sqrt(weighted_square_sum(x, w) / static_cast<double>(NV_LENGTH_S(x)));
}

void compare(double c, N_Vector x, N_Vector z) {
  const View xv(x), zv(z);
  for (sunindextype i = 0; i < xv.size; ++i) zv.data[i] = std::abs(xv.data[i]) >= c ? 1.0 : 0.0;
}

int linear_combination(int count, double* c, N_Vector* X, N_Vector z) {
  if (count == 1) {
    scale(c[0], X[0], z);
    return 0;
  }
  if (count == 2) {
    linear_sum(c[0], X[0], c[1], X[1], z);
    return 0;
  }
  const View zv(z);
  double* zd = zv.data;
  if (X[0] == z && c[0] == 1.0) {
    for (int k = 1; k < count; ++k) {
      const double* xd = NV_DATA_S(X[k]);
      for (sunindextype i = 0; i < zv.size; ++i) zd[i] += c[k] * xd[i];
    }
    return 0;
  }
  if (X[0] == z) {
    for (sunindextype i = 0; i < zv.size; ++i) zd[i] *= c[0];
  } else {
    const double* x0 = NV_DATA_S(X[0]);
    for (sunindextype i = 0; i < zv.size; ++i) zd[i] = c[0] * x0[i];
  }
  for (int k = 1; k < count; ++k) {
    const double* xd = NV_DATA_S(X[k]);
    for (sunindextype i = 0; i < zv.size; ++i) zd[i] += c[k] * xd[i];
  }
  return 0;
}

int scale_add_multi(int count, double* a, N_Vector x, N_Vector* Y, N_Vector* Z) {
  if (count == 1) {
    linear_sum(a[0], x, 1.0, Y[0], Z[0]);
    return 0;
  }
  const View xv(x);
  const double* xd = xv.data;
  for (int k = 0; k < count; ++k) {
    const double* yd = NV_DATA_S(Y[k]);
    double* zd = NV_DATA_S(Z[k]);
    if (Y == Z) {
      for (sunindextype i = 0; i < xv.size; ++i) zd[i] += a[k] * xd[i];
    } else {
      for (sunindextype i = 0; i < xv.size; ++i) zd[i] = a[k] * xd[i] + yd[i];
    }
  }
  return 0;
}

}  // namespace

void install_optimised_serial_kernels(N_Vector v) {
  N_VEnableFusedOps_Serial(v, SUNTRUE);  // CVODE then calls the fused forms
  N_Vector_Ops ops = v->ops;
  ops->nvlinearsum = linear_sum;
  ops->nvconst = constant;
  ops->nvprod = product;
  ops->nvdiv = quotient;
  ops->nvscale = scale;
  ops->nvabs = absolute;
  ops->nvinv = inverse;
  ops->nvaddconst = add_constant;
  ops->nvmaxnorm = max_norm;
  ops->nvwrmsnorm = weighted_rms_norm;
  ops->nvwsqrsumlocal = weighted_square_sum;
  ops->nvcompare = compare;
  ops->nvlinearcombination = linear_combination;
  ops->nvscaleaddmulti = scale_add_multi;
}

}  // namespace tcpmsim
