// The compiled tape (gen/sym/evaluate): a block of points at once gives, bit for bit, what one
// point at a time gives, and both agree with the independent shadow evaluation; registers are
// reused, so the working set is the tape's width, not its length.
#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

#include "random_expr.hpp"
#include "sym/print.hpp"

namespace dyncc::sym {
namespace {

using test::Generator;
using test::Point;
using test::Sample;

// Column-major rows x inputs: input i of point r at [i * rows + r].
std::vector<double> stacked(const std::vector<Point>& points) {
  std::vector<double> out(points.size() * test::kNumSymbols);
  for (std::size_t r = 0; r < points.size(); ++r) {
    for (std::size_t i = 0; i < test::kNumSymbols; ++i) out[i * points.size() + r] = points[r][i];
  }
  return out;
}

TEST(SymEvaluateRows, EveryPointAsOnePointAtATimeAndAsTheShadow) {
  Generator gen(0xB10C);
  // Row counts around the block length (64) and below it, and none at all.
  for (const std::size_t rows : {0U, 1U, 5U, 63U, 64U, 65U, 130U}) {
    std::vector<Sample> samples;
    std::vector<Expr> outputs;
    for (int k = 0; k < 6; ++k) {
      samples.push_back(gen.expression(3));
      outputs.push_back(samples.back().expr);
    }
    // Outputs sharing subexpressions with each other: their sum and product.
    outputs.push_back(outputs[0] + outputs[1]);
    outputs.push_back(outputs[2] * outputs[3]);
    const CompiledFunction f(outputs, test::all_symbols());
    std::vector<Point> points;
    for (std::size_t r = 0; r < rows; ++r) points.push_back(gen.point());
    std::vector<double> values(outputs.size() * rows);
    f.evaluate_rows(stacked(points), rows, values);
    for (std::size_t r = 0; r < rows; ++r) {
      const std::vector<double> one = f(points[r]);
      for (std::size_t k = 0; k < outputs.size(); ++k) {
        EXPECT_EQ(values[k * rows + r], one[k]) << "rows " << rows << ", point " << r << ", " << to_string(outputs[k]);
      }
      for (std::size_t k = 0; k < samples.size(); ++k) {
        EXPECT_TRUE(test::close(one[k], samples[k](points[r]), 1e-9)) << to_string(outputs[k]);
      }
      EXPECT_TRUE(test::close(one[6], samples[0](points[r]) + samples[1](points[r]), 1e-9));
      EXPECT_TRUE(test::close(one[7], samples[2](points[r]) * samples[3](points[r]), 1e-9));
    }
  }
}

TEST(SymEvaluateRows, OutputsThatAreInputsConstantsOrRepeated) {
  const Expr x = symbol("x"), y = symbol("y");
  const Expr inputs[] = {x, y};
  const Expr outputs[] = {y, Expr(3), x * y, x, x * y, sin(x) + pow(y, 3), pi()};
  const CompiledFunction f(outputs, inputs);
  const std::size_t rows = 70;
  std::vector<double> in(2 * rows), out(std::size(outputs) * rows);
  for (std::size_t r = 0; r < rows; ++r) {
    in[r] = 0.1 * static_cast<double>(r) - 3.0;
    in[rows + r] = 1.0 - 0.05 * static_cast<double>(r);
  }
  f.evaluate_rows(in, rows, out);
  for (std::size_t r = 0; r < rows; ++r) {
    const double xv = in[r], yv = in[rows + r];
    EXPECT_EQ(out[0 * rows + r], yv);
    EXPECT_EQ(out[1 * rows + r], 3.0);
    EXPECT_DOUBLE_EQ(out[2 * rows + r], xv * yv);
    EXPECT_EQ(out[3 * rows + r], xv);
    EXPECT_EQ(out[4 * rows + r], out[2 * rows + r]);
    EXPECT_NEAR(out[5 * rows + r], std::sin(xv) + yv * yv * yv, 1e-12);
    EXPECT_DOUBLE_EQ(out[6 * rows + r], 3.141592653589793);
  }
}

// A sum of 200 squares, each of its own sines and cosines: the tape is 2000 instructions long, but
// the widest point is the 200 terms waiting for the (one, n-ary) sum: each term's intermediates
// are dead once the term is built, so about 200 registers carry the whole tape.
TEST(SymEvaluateRows, RegistersAreReusedOnceTheirLastReaderHasRun) {
  const Expr x = symbol("x"), y = symbol("y");
  Expr sum(0);
  for (int k = 1; k <= 200; ++k) {
    const Expr term = sin(Expr(k) * x) * cos(Expr(k) * y + Expr(1)) + Expr(k) * pow(sin(x + Expr(k)), 2);
    sum = sum + term * term;
  }
  const Expr inputs[] = {x, y};
  const Expr outputs[] = {sum};
  const CompiledFunction f(outputs, inputs);
  EXPECT_GT(f.instruction_count(), 1000U);
  EXPECT_LE(f.register_count(), 2U + 200U + 10U) << "instructions " << f.instruction_count();
  double expected = 0.0;
  const double xv = 0.3, yv = -1.1;
  for (int k = 1; k <= 200; ++k) {
    const double term = std::sin(k * xv) * std::cos(k * yv + 1) + k * std::pow(std::sin(xv + k), 2);
    expected += term * term;
  }
  EXPECT_TRUE(test::close(f(std::vector<double>{xv, yv})[0], expected, 1e-11));
}

TEST(SymEvaluateRows, WrongSizesAndMissingSymbolsAreErrors) {
  const Expr x = symbol("x"), y = symbol("y");
  const Expr inputs[] = {x};
  const Expr outputs[] = {sin(x), x * x};
  const CompiledFunction f(outputs, inputs);
  std::vector<double> in(10), out(20);
  EXPECT_NO_THROW(f.evaluate_rows(in, 10, out));
  EXPECT_THROW(f.evaluate_rows(in, 9, out), std::invalid_argument);
  std::vector<double> short_out(19);
  EXPECT_THROW(f.evaluate_rows(in, 10, short_out), std::invalid_argument);
  const Expr with_y[] = {x * y};
  EXPECT_THROW(CompiledFunction(with_y, inputs), std::invalid_argument);
}

}  // namespace
}  // namespace dyncc::sym
