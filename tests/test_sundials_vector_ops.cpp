// The compiled serial-vector operations (integrators/sundials_vector_ops.hpp) stand in for the
// library's -O0 ones inside CVODE and ARKODE; they must give the library's results bit for bit,
// in every case distinction the library makes (a = b = 1, a = -b, aliasing, ...), or the study's
// numbers would change with the speed-up. Also: clones inherit them, which is how the solvers'
// work vectors get them.
#include "sundials_handles.hpp"
#include "sundials_vector_ops.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

using namespace contact::sundials;

namespace {

constexpr sunindextype kN = 37;

class VectorOps : public ::testing::Test {
 protected:
  VectorOps() {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-3.0, 3.0);
    for (auto* v : {&x_, &y_, &w_}) {
      v->resize(kN);
      for (auto& e : *v) e = u(rng);
    }
    w_[3] = 0.0;  // a zero, for inv and div to meet
  }
  // A library vector and a compiled one holding `data`.
  NVector library(const std::vector<double>& data) const { return make(data, false); }
  NVector compiled(const std::vector<double>& data) const { return make(data, true); }
  static bool same(N_Vector a, N_Vector b) {  // bitwise, NaNs and signed zeros included
    return std::memcmp(N_VGetArrayPointer(a), N_VGetArrayPointer(b), kN * sizeof(double)) == 0;
  }

  Context ctx_ = make_context();
  std::vector<double> x_, y_, w_;

 private:
  NVector make(const std::vector<double>& data, bool ours) const {
    NVector v(N_VNew_Serial(kN, ctx_.get()));
    if (ours) use_compiled_vector_ops(v.get());
    std::copy(data.begin(), data.end(), N_VGetArrayPointer(v.get()));
    return v;
  }
};

TEST_F(VectorOps, LinearSumMatchesTheLibraryInEveryCase) {
  const std::vector<std::pair<double, double>> coefficients = {{1, 1},      {1, -1},    {-1, 1},   {1, 0.3},
                                                               {0.3, 1},    {-1, 0.3},  {0.3, -1}, {0.7, 0.7},
                                                               {0.7, -0.7}, {0.7, 0.2}, {-1, -1}};
  for (const auto& [a, b] : coefficients)
    for (int alias = 0; alias < 3; ++alias) {  // z separate, z = x, z = y
      NVector lx = library(x_), ly = library(y_), lz = library(w_);
      NVector cx = compiled(x_), cy = compiled(y_), cz = compiled(w_);
      N_Vector lout = alias == 1 ? lx.get() : alias == 2 ? ly.get() : lz.get();
      N_Vector cout = alias == 1 ? cx.get() : alias == 2 ? cy.get() : cz.get();
      N_VLinearSum_Serial(a, lx.get(), b, ly.get(), lout);
      N_VLinearSum(a, cx.get(), b, cy.get(), cout);
      EXPECT_TRUE(same(lout, cout)) << "a = " << a << ", b = " << b << ", alias " << alias;
    }
}

TEST_F(VectorOps, ElementwiseOperationsAndNormsMatchTheLibrary) {
  for (double c : {1.0, -1.0, 0.37}) {
    NVector lx = library(x_), lz = library(w_), cx = compiled(x_), cz = compiled(w_);
    N_VScale_Serial(c, lx.get(), lz.get());
    N_VScale(c, cx.get(), cz.get());
    EXPECT_TRUE(same(lz.get(), cz.get())) << "scale " << c;
    N_VScale_Serial(c, lx.get(), lx.get());
    N_VScale(c, cx.get(), cx.get());
    EXPECT_TRUE(same(lx.get(), cx.get())) << "scale in place " << c;
  }
  NVector lx = library(x_), ly = library(w_), lz = library(y_);
  NVector cx = compiled(x_), cy = compiled(w_), cz = compiled(y_);
  N_VProd_Serial(lx.get(), ly.get(), lz.get());
  N_VProd(cx.get(), cy.get(), cz.get());
  EXPECT_TRUE(same(lz.get(), cz.get())) << "prod";
  N_VDiv_Serial(lx.get(), ly.get(), lz.get());
  N_VDiv(cx.get(), cy.get(), cz.get());
  EXPECT_TRUE(same(lz.get(), cz.get())) << "div (with a division by zero)";
  N_VInv_Serial(ly.get(), lz.get());
  N_VInv(cy.get(), cz.get());
  EXPECT_TRUE(same(lz.get(), cz.get())) << "inv (with a zero)";
  N_VAbs_Serial(lx.get(), lz.get());
  N_VAbs(cx.get(), cz.get());
  EXPECT_TRUE(same(lz.get(), cz.get())) << "abs";
  N_VAddConst_Serial(lx.get(), 0.125, lz.get());
  N_VAddConst(cx.get(), 0.125, cz.get());
  EXPECT_TRUE(same(lz.get(), cz.get())) << "add const";
  N_VConst_Serial(-2.5, lz.get());
  N_VConst(-2.5, cz.get());
  EXPECT_TRUE(same(lz.get(), cz.get())) << "const";
  // Norms: equal as doubles (the same sequential sums), not merely close.
  EXPECT_EQ(N_VWrmsNorm_Serial(lx.get(), ly.get()), N_VWrmsNorm(cx.get(), cy.get()));
  EXPECT_EQ(N_VWSqrSumLocal_Serial(lx.get(), ly.get()), N_VWSqrSumLocal(cx.get(), cy.get()));
  EXPECT_EQ(N_VMaxNorm_Serial(lx.get()), N_VMaxNorm(cx.get()));
  EXPECT_EQ(N_VDotProd_Serial(lx.get(), ly.get()), N_VDotProd(cx.get(), cy.get()));
  EXPECT_EQ(N_VDotProd_Serial(lx.get(), ly.get()), N_VDotProdLocal(cx.get(), cy.get()));
}

// The library's serial vectors leave the fused operations out (it then loops over scale and
// linear sum); ours fuse them into one pass with the same arithmetic.
TEST_F(VectorOps, FusedOperationsMatchTheLibrarysFallback) {
  std::vector<double> c = {1.0, -1.0, 0.3, -2.5};
  for (bool in_place : {false, true}) {
    NVector l0 = library(x_), l1 = library(y_), l2 = library(w_), l3 = library(x_), lz = library(y_);
    NVector c0 = compiled(x_), c1 = compiled(y_), c2 = compiled(w_), c3 = compiled(x_), cz = compiled(y_);
    std::vector<N_Vector> LX = {l0.get(), l1.get(), l2.get(), l3.get()},
                          CX = {c0.get(), c1.get(), c2.get(), c3.get()};
    for (double c_first : {1.0, 0.7}) {
      c[0] = c_first;
      N_Vector lout = in_place ? LX[0] : lz.get(), cout = in_place ? CX[0] : cz.get();
      ASSERT_EQ(N_VLinearCombination(4, c.data(), LX.data(), lout), 0);
      ASSERT_EQ(N_VLinearCombination(4, c.data(), CX.data(), cout), 0);
      EXPECT_TRUE(same(lout, cout)) << "linear combination, in place " << in_place << ", c0 = " << c_first;
    }
    std::vector<N_Vector> LZ = {lz.get(), l3.get()}, CZ = {cz.get(), c3.get()};
    std::vector<N_Vector> LY = {l1.get(), l2.get()}, CY = {c1.get(), c2.get()};
    ASSERT_EQ(N_VScaleAddMulti(2, c.data() + 1, l0.get(), LY.data(), in_place ? LY.data() : LZ.data()), 0);
    ASSERT_EQ(N_VScaleAddMulti(2, c.data() + 1, c0.get(), CY.data(), in_place ? CY.data() : CZ.data()), 0);
    for (int k = 0; k < 2; ++k)
      EXPECT_TRUE(same(in_place ? LY[k] : LZ[k], in_place ? CY[k] : CZ[k])) << "scale add multi " << k;
  }
}

TEST_F(VectorOps, ClonesInheritTheCompiledOperations) {
  NVector v = compiled(x_);
  NVector clone(N_VClone(v.get()));
  ASSERT_TRUE(clone);
  EXPECT_EQ(clone->ops->nvlinearsum, v->ops->nvlinearsum);
  EXPECT_NE(clone->ops->nvlinearsum, N_VLinearSum_Serial);
  EXPECT_NE(clone->ops->nvwrmsnorm, N_VWrmsNorm_Serial);
  EXPECT_NE(clone->ops->nvdotprod, N_VDotProd_Serial);  // GMRES's inner products
}

}  // namespace
