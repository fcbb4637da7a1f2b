// SPDX-License-Identifier: GPL-3.0-or-later
#include "integrators/sundials/vector_ops.hpp"

#include <gtest/gtest.h>

#include <nvector/nvector_serial.h>

#include <random>

#include "integrators/sundials/handles.hpp"

namespace roifem::integrators::sundials {
namespace {

// Each replaced operation against NVECTOR_SERIAL's own, on random vectors of an odd length
// (so that SIMD remainders are exercised).
class VectorOps : public ::testing::Test {
 protected:
  static constexpr sunindextype n = 1001;
  Context context = make_context();
  Vector stock_x{N_VNew_Serial(n, context.get())}, stock_y{N_VNew_Serial(n, context.get())},
      stock_z{N_VNew_Serial(n, context.get())};
  Vector fast_x = make_vector(n, context.get()), fast_y = make_vector(n, context.get()), fast_z = make_vector(n, context.get());

  void SetUp() override {
    std::mt19937 random(7);
    std::uniform_real_distribution<double> value(0.5, 2.0);
    for (sunindextype i = 0; i < n; ++i) {
      NV_Ith_S(stock_x.get(), i) = NV_Ith_S(fast_x.get(), i) = (i % 3 == 0 ? -1 : 1) * value(random);
      NV_Ith_S(stock_y.get(), i) = NV_Ith_S(fast_y.get(), i) = value(random);
    }
  }
  double difference() { return (view(stock_z.get()) - view(fast_z.get())).lpNorm<Eigen::Infinity>(); }
};

TEST_F(VectorOps, ElementWiseOperationsEqualTheLibrarys) {
  N_VLinearSum(0.3, stock_x.get(), -1.7, stock_y.get(), stock_z.get());
  N_VLinearSum(0.3, fast_x.get(), -1.7, fast_y.get(), fast_z.get());
  EXPECT_LT(difference(), 1e-15);
  N_VProd(stock_x.get(), stock_y.get(), stock_z.get());
  N_VProd(fast_x.get(), fast_y.get(), fast_z.get());
  EXPECT_EQ(difference(), 0.0);
  N_VScale(-2.5, stock_x.get(), stock_z.get());
  N_VScale(-2.5, fast_x.get(), fast_z.get());
  EXPECT_EQ(difference(), 0.0);
  N_VAbs(stock_x.get(), stock_z.get());
  N_VAbs(fast_x.get(), fast_z.get());
  EXPECT_EQ(difference(), 0.0);
  N_VInv(stock_y.get(), stock_z.get());
  N_VInv(fast_y.get(), fast_z.get());
  EXPECT_EQ(difference(), 0.0);
  N_VAddConst(stock_x.get(), 0.25, stock_z.get());
  N_VAddConst(fast_x.get(), 0.25, fast_z.get());
  EXPECT_EQ(difference(), 0.0);
  N_VConst(3.5, stock_z.get());
  N_VConst(3.5, fast_z.get());
  EXPECT_EQ(difference(), 0.0);
}

TEST_F(VectorOps, NormsEqualTheLibrarysToRounding) {
  EXPECT_NEAR(N_VWrmsNorm(fast_x.get(), fast_y.get()), N_VWrmsNorm(stock_x.get(), stock_y.get()), 1e-14);
  EXPECT_NEAR(N_VDotProd(fast_x.get(), fast_y.get()), N_VDotProd(stock_x.get(), stock_y.get()), 1e-12);
  EXPECT_EQ(N_VMaxNorm(fast_x.get()), N_VMaxNorm(stock_x.get()));
}

TEST_F(VectorOps, FusedOperationsEqualTheLibrarysAndClonesInheritThem) {
  Vector fast_w{N_VClone(fast_x.get())}, stock_w{N_VClone(stock_x.get())};
  EXPECT_EQ(fast_w.get()->ops->nvwrmsnorm, fast_x.get()->ops->nvwrmsnorm);
  N_VScale(1.0, fast_y.get(), fast_w.get());
  N_VScale(1.0, stock_y.get(), stock_w.get());
  double c[3] = {0.5, -1.25, 2.0};
  N_Vector stock[3] = {stock_x.get(), stock_y.get(), stock_w.get()}, fast[3] = {fast_x.get(), fast_y.get(), fast_w.get()};
  N_VLinearCombination(3, c, stock, stock_z.get());
  N_VLinearCombination(3, c, fast, fast_z.get());
  EXPECT_LT(difference(), 1e-14);
  // In place: z = c0 z + c1 y.
  N_Vector stock_in_place[2] = {stock_z.get(), stock_y.get()}, fast_in_place[2] = {fast_z.get(), fast_y.get()};
  N_VLinearCombination(2, c, stock_in_place, stock_z.get());
  N_VLinearCombination(2, c, fast_in_place, fast_z.get());
  EXPECT_LT(difference(), 1e-14);
  N_Vector stock_out[1] = {stock_z.get()}, fast_out[1] = {fast_z.get()}, stock_in[1] = {stock_y.get()},
           fast_in[1] = {fast_y.get()};
  N_VScaleAddMulti(1, c + 2, stock_x.get(), stock_in, stock_out);
  N_VScaleAddMulti(1, c + 2, fast_x.get(), fast_in, fast_out);
  EXPECT_LT(difference(), 1e-15);
}

}  // namespace
}  // namespace roifem::integrators::sundials
