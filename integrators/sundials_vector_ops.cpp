#include "sundials_vector_ops.hpp"

#include <cmath>

namespace contact::sundials {

namespace {

struct View {
  sunindextype n;
  sunrealtype* d;
};
View view(N_Vector v) { return {NV_LENGTH_S(v), NV_DATA_S(v)}; }

// z = a x + b y, with the library's special cases (their roundings differ: c (x + y) is not
// c x + c y).
void linear_sum(sunrealtype a, N_Vector x, sunrealtype b, N_Vector y, N_Vector z) {
  const auto [n, xd] = view(x);
  sunrealtype* yd = NV_DATA_S(y);
  sunrealtype* zd = NV_DATA_S(z);
  auto axpy = [n = n](sunrealtype c, const sunrealtype* u, sunrealtype* w) {  // w += c u
    if (c == 1.0)
      for (sunindextype i = 0; i < n; ++i) w[i] += u[i];
    else if (c == -1.0)
      for (sunindextype i = 0; i < n; ++i) w[i] -= u[i];
    else
      for (sunindextype i = 0; i < n; ++i) w[i] += c * u[i];
  };
  if (b == 1.0 && z == y) return axpy(a, xd, yd);
  if (a == 1.0 && z == x) return axpy(b, yd, xd);
  if (a == 1.0 && b == 1.0) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i] + yd[i];
  } else if ((a == 1.0 && b == -1.0) || (a == -1.0 && b == 1.0)) {
    const sunrealtype* p = a == 1.0 ? xd : yd;  // p - q
    const sunrealtype* q = a == 1.0 ? yd : xd;
    for (sunindextype i = 0; i < n; ++i) zd[i] = p[i] - q[i];
  } else if (a == 1.0 || b == 1.0) {  // c u + w
    const sunrealtype c = a == 1.0 ? b : a;
    const sunrealtype* u = a == 1.0 ? yd : xd;
    const sunrealtype* w = a == 1.0 ? xd : yd;
    for (sunindextype i = 0; i < n; ++i) zd[i] = c * u[i] + w[i];
  } else if (a == -1.0 || b == -1.0) {  // c u - w
    const sunrealtype c = a == -1.0 ? b : a;
    const sunrealtype* u = a == -1.0 ? yd : xd;
    const sunrealtype* w = a == -1.0 ? xd : yd;
    for (sunindextype i = 0; i < n; ++i) zd[i] = c * u[i] - w[i];
  } else if (a == b) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * (xd[i] + yd[i]);
  } else if (a == -b) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * (xd[i] - yd[i]);
  } else {
    for (sunindextype i = 0; i < n; ++i) zd[i] = a * xd[i] + b * yd[i];
  }
}

void constant(sunrealtype c, N_Vector z) {
  const auto [n, zd] = view(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = c;
}

void scale(sunrealtype c, N_Vector x, N_Vector z) {
  const auto [n, xd] = view(x);
  sunrealtype* zd = NV_DATA_S(z);
  if (c == 1.0) {
    if (z != x)
      for (sunindextype i = 0; i < n; ++i) zd[i] = xd[i];
  } else if (c == -1.0) {
    for (sunindextype i = 0; i < n; ++i) zd[i] = -xd[i];
  } else {
    for (sunindextype i = 0; i < n; ++i) zd[i] = c * xd[i];
  }
}

// z_i = f(x_i) and z_i = f(x_i, y_i): element-wise maps, z may alias x or y.
template <class F>
void map(N_Vector x, N_Vector z, F f) {
  const auto [n, xd] = view(x);
  sunrealtype* zd = NV_DATA_S(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = f(xd[i]);
}
template <class F>
void map(N_Vector x, N_Vector y, N_Vector z, F f) {
  const auto [n, xd] = view(x);
  const sunrealtype* yd = NV_DATA_S(y);
  sunrealtype* zd = NV_DATA_S(z);
  for (sunindextype i = 0; i < n; ++i) zd[i] = f(xd[i], yd[i]);
}

void prod(N_Vector x, N_Vector y, N_Vector z) {
  map(x, y, z, [](sunrealtype a, sunrealtype b) { return a * b; });
}
void div(N_Vector x, N_Vector y, N_Vector z) {
  map(x, y, z, [](sunrealtype a, sunrealtype b) { return a / b; });
}
void abs(N_Vector x, N_Vector z) {
  map(x, z, [](sunrealtype a) { return std::fabs(a); });
}
void inv(N_Vector x, N_Vector z) {
  map(x, z, [](sunrealtype a) { return 1.0 / a; });
}
void add_const(N_Vector x, sunrealtype b, N_Vector z) {
  map(x, z, [b](sunrealtype a) { return a + b; });
}

// Sequential sums, as the library's: the compiler may not reorder them (no -ffast-math).
sunrealtype weighted_square_sum(N_Vector x, N_Vector w) {
  const auto [n, xd] = view(x);
  const sunrealtype* wd = NV_DATA_S(w);
  sunrealtype sum = 0.0;
  for (sunindextype i = 0; i < n; ++i) {
    const sunrealtype p = xd[i] * wd[i];
    sum += p * p;
  }
  return sum;
}

// GMRES's inner products (its Gram-Schmidt steps and norms).
sunrealtype dot_product(N_Vector x, N_Vector y) {
  const auto [n, xd] = view(x);
  const sunrealtype* yd = NV_DATA_S(y);
  sunrealtype sum = 0.0;
  for (sunindextype i = 0; i < n; ++i) sum += xd[i] * yd[i];
  return sum;
}

sunrealtype wrms_norm(N_Vector x, N_Vector w) {
  return std::sqrt(weighted_square_sum(x, w) / static_cast<sunrealtype>(NV_LENGTH_S(x)));
}

sunrealtype max_norm(N_Vector x) {
  const auto [n, xd] = view(x);
  sunrealtype m = 0.0;
  for (sunindextype i = 0; i < n; ++i)
    if (std::fabs(xd[i]) > m) m = std::fabs(xd[i]);
  return m;
}

// The fused operations CVODE and ARKODE use for their Nordsieck arrays and dense output. Without
// them the library falls back to one scale and nvec - 1 linear sums, whose arithmetic is the same
// (z = c0 X0, then z += c_i X_i; Z_i = a_i x + Y_i): one pass instead of nvec calls.
int linear_combination(int nvec, sunrealtype* c, N_Vector* X, N_Vector z) {
  scale(c[0], X[0], z);
  const auto [n, zd] = view(z);
  for (int k = 1; k < nvec; ++k) {
    const sunrealtype* xd = NV_DATA_S(X[k]);
    const sunrealtype ck = c[k];
    for (sunindextype i = 0; i < n; ++i) zd[i] += ck * xd[i];
  }
  return 0;
}

int scale_add_multi(int nvec, sunrealtype* a, N_Vector x, N_Vector* Y, N_Vector* Z) {
  const auto [n, xd] = view(x);
  for (int k = 0; k < nvec; ++k) {
    const sunrealtype* yd = NV_DATA_S(Y[k]);
    sunrealtype* zd = NV_DATA_S(Z[k]);
    const sunrealtype ak = a[k];
    for (sunindextype i = 0; i < n; ++i) zd[i] = ak * xd[i] + yd[i];
  }
  return 0;
}

}  // namespace

void use_compiled_vector_ops(N_Vector v) {
  N_Vector_Ops ops = v->ops;
  ops->nvlinearsum = linear_sum;
  ops->nvconst = constant;
  ops->nvscale = scale;
  ops->nvprod = prod;
  ops->nvdiv = div;
  ops->nvabs = abs;
  ops->nvinv = inv;
  ops->nvaddconst = add_const;
  ops->nvdotprod = dot_product;
  ops->nvdotprodlocal = dot_product;
  ops->nvwrmsnorm = wrms_norm;
  ops->nvwsqrsumlocal = weighted_square_sum;
  ops->nvmaxnorm = max_norm;
  ops->nvmaxnormlocal = max_norm;
  ops->nvlinearcombination = linear_combination;
  ops->nvscaleaddmulti = scale_add_multi;
}

}  // namespace contact::sundials
