// Tests for deme::Expression, the prescribed-motion expression compiler.
#include "codegen/Expression.h"

#include <deme/Error.h>
#include <deme/VariableTypes.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

using deme::Expression;

namespace {

const std::vector<std::string> kT = {"t"};

double eval(const std::string& text, double t = 0.0) { return Expression::parse(text, kT, "test").evaluate(&t); }

// Parses `text`, expects a deme::Error, and returns its message.
std::string parseError(const std::string& text, const std::string& call = "setPrescribedMotion") {
    try {
        Expression::parse(text, kT, call);
    } catch (const deme::Error& e) {
        return e.what();
    }
    ADD_FAILURE() << "no error for \"" << text << "\"";
    return "";
}

// Every error must name the call and quote the expression text.
void expectError(const std::string& text, const std::string& fragment) {
    const std::string msg = parseError(text);
    EXPECT_NE(msg.find("setPrescribedMotion"), std::string::npos) << msg;
    EXPECT_NE(msg.find("\"" + text + "\""), std::string::npos) << msg;
    EXPECT_NE(msg.find(fragment), std::string::npos) << "expected '" << fragment << "' in: " << msg;
}

}  // namespace

TEST(Expression, DefaultIsZero) {
    Expression e;
    EXPECT_EQ(e.evaluate(nullptr), 0.0);
    EXPECT_TRUE(e.isConstant());
    EXPECT_EQ(e.text(), "");
}

TEST(Expression, Literals) {
    EXPECT_DOUBLE_EQ(eval("3.14159"), 3.14159);
    EXPECT_DOUBLE_EQ(eval("3"), 3.0);
    EXPECT_DOUBLE_EQ(eval(".5"), 0.5);
    EXPECT_DOUBLE_EQ(eval("1."), 1.0);
    EXPECT_DOUBLE_EQ(eval("1e-3"), 1e-3);
    EXPECT_DOUBLE_EQ(eval("2.5E+2"), 250.0);
    EXPECT_DOUBLE_EQ(eval("1.5f"), 1.5);
    EXPECT_DOUBLE_EQ(eval("2.5e1F"), 25.0);
}

TEST(Expression, SineOfTime) {
    for (double t : {0.0, 0.3, 1.0, 2.7, -4.2, 100.0}) {
        EXPECT_DOUBLE_EQ(eval("0.1*sin(t)", t), 0.1 * std::sin(t)) << t;
        EXPECT_DOUBLE_EQ(eval("-2*pi*cos(2*pi*t) + 0.5", t), -2 * deme::PI * std::cos(2 * deme::PI * t) + 0.5) << t;
    }
}

TEST(Expression, PrecedenceAndAssociativity) {
    EXPECT_EQ(eval("2+3*4"), 14.0);
    EXPECT_EQ(eval("(2+3)*4"), 20.0);
    EXPECT_EQ(eval("10-4-3"), 3.0);
    EXPECT_EQ(eval("16/4/2"), 2.0);
    EXPECT_EQ(eval("-2*3"), -6.0);
    EXPECT_EQ(eval("2*-3"), -6.0);
    EXPECT_EQ(eval("- -3"), 3.0);
    EXPECT_EQ(eval("+3 - +2"), 1.0);
    EXPECT_EQ(eval("-t*t", 3.0), -9.0);
    EXPECT_EQ(eval("2 - -t", 3.0), 5.0);
    EXPECT_EQ(eval("1/2"), 0.5);  // all arithmetic is double, unlike C++ integer division
}

TEST(Expression, Functions) {
    const double t = 0.7;
    EXPECT_DOUBLE_EQ(eval("atan2(1,2)"), std::atan2(1.0, 2.0));
    EXPECT_DOUBLE_EQ(eval("pow(t,3)", t), std::pow(t, 3.0));
    EXPECT_DOUBLE_EQ(eval("sqrt(exp(t)) + log(t) - log10(t)", t), std::sqrt(std::exp(t)) + std::log(t) - std::log10(t));
    EXPECT_DOUBLE_EQ(eval("sin(cos(tan(t)))", t), std::sin(std::cos(std::tan(t))));
    EXPECT_DOUBLE_EQ(eval("asin(t)+acos(t)+atan(t)", t), std::asin(t) + std::acos(t) + std::atan(t));
    EXPECT_DOUBLE_EQ(eval("sinh(t)*cosh(t)/tanh(t)", t), std::sinh(t) * std::cosh(t) / std::tanh(t));
    EXPECT_EQ(eval("abs(-t) + fabs(-1)", t), t + 1.0);
    EXPECT_EQ(eval("floor(t) + ceil(t)", t), 1.0);
    EXPECT_EQ(eval("fmin(t, 0.5) + fmax(t, 0.5)", t), 0.5 + t);
    EXPECT_EQ(eval("min(t, 2) * max(t, 2)", t), 2 * t);
    EXPECT_DOUBLE_EQ(eval("fmod(t, 0.25)", t), std::fmod(t, 0.25));
    EXPECT_DOUBLE_EQ(eval("std::sin(t) * deme::PI + PI", t), std::sin(t) * deme::PI + deme::PI);
    EXPECT_DOUBLE_EQ(eval("pow(max(sin(t), 0.1), atan2(t, 1 + t*t))", t),
                     std::pow(std::max(std::sin(t), 0.1), std::atan2(t, 1 + t * t)));
}

TEST(Expression, Whitespace) {
    EXPECT_DOUBLE_EQ(eval(" \t0.1 *  sin ( t )\n", 2.0), 0.1 * std::sin(2.0));
    EXPECT_DOUBLE_EQ(eval("atan2 ( 1 , 2 )"), std::atan2(1.0, 2.0));
}

TEST(Expression, SeveralVariables) {
    const Expression e = Expression::parse("x*y - t", {"t", "x", "y"}, "test");
    const double v[] = {1.0, 2.0, 5.0};
    EXPECT_EQ(e.evaluate(v), 9.0);
    EXPECT_FALSE(e.isConstant());
}

TEST(Expression, ConstantDetection) {
    EXPECT_TRUE(Expression::parse("3.14159", kT, "test").isConstant());
    EXPECT_TRUE(Expression::parse("-2*pi*cos(2*pi) + sqrt(2)", kT, "test").isConstant());
    EXPECT_FALSE(Expression::parse("t", kT, "test").isConstant());
    EXPECT_FALSE(Expression::parse("0*t", kT, "test").isConstant());  // references t, so not constant
    EXPECT_FALSE(Expression::parse("0.1*sin(t)", kT, "test").isConstant());
    // A constant needs no variable values at all.
    EXPECT_DOUBLE_EQ(Expression::parse("2*pi", kT, "test").evaluate(nullptr), 2 * deme::PI);
}

TEST(Expression, TextIsKeptAndCopiesWork) {
    const Expression e = Expression::parse("0.1*sin(t)", kT, "test");
    EXPECT_EQ(e.text(), "0.1*sin(t)");
    Expression copy;
    copy = e;
    const double t = 1.0;
    EXPECT_EQ(copy.evaluate(&t), e.evaluate(&t));
    EXPECT_EQ(copy.text(), e.text());
}

TEST(Expression, ErrorsNameCallTextAndPosition) {
    expectError("", "empty");
    expectError("   ", "empty");
    expectError("sin(", "position 5");
    expectError("2+*3", "position 3");
    expectError("foo", "unknown name 'foo'");
    expectError("foo(t)", "unknown function 'foo'");
    expectError("sin(1,2)", "takes 1 argument");
    expectError("atan2(1)", "takes 2 arguments");
    expectError("pow()", "takes 2 arguments");
    expectError("0.1*sin(t) t", "position 12");
    expectError("1 2", "position 3");
    expectError("(1+2", "expected ')'");
    expectError("1+2)", "position 4");
    expectError("sin", "must be called");
    expectError("t(1)", "not a function");
    expectError("pi(1)", "not a function");
    expectError("1e+", "exponent");
    expectError("1.5ff", "malformed number");
    expectError("2t", "position 2");
    expectError("1.2.3", "malformed number");
    expectError("1e999", "out of the range");
    expectError("3 % 2", "'%'");
    expectError("sin(t,)", "position 7");
}

TEST(Expression, CaretIsRejectedWithPowHint) {
    expectError("-2^2", "pow(");
    expectError("t^2", "position 2");
    expectError("2*^3", "pow(");
}

TEST(Expression, PathologicalNestingIsRejectedNotCrashing) {
    expectError(std::string(10000, '(') + "1" + std::string(10000, ')'), "nested too deeply");
    std::string deep = "t";
    for (int i = 0; i < 100; ++i) deep = "t+(" + deep + ")";
    expectError(deep, "too complex");
    // Reasonable nesting still works.
    EXPECT_EQ(eval(std::string(50, '(') + "t" + std::string(50, ')'), 2.0), 2.0);
}

// ---- C++ source for run-time compiled kernels (the GPU's prescriptions)
std::string cpp(const std::string& text) { return Expression::parse(text, kT, "test").toCppSource({"t"}); }

TEST(ExpressionCppSource, ParenthesisesEveryOperationAndWritesExactConstants) {
    // 0.1 is not a binary fraction: the hexadecimal literal carries its double exactly.
    EXPECT_EQ(cpp("0.1*sin(t)"), "((0x1.999999999999ap-4) * (sin(t)))");
    // Left associativity and the unary minus survive as explicit parentheses.
    EXPECT_EQ(cpp("t-t-t"), "(((t) - (t)) - (t))");
    EXPECT_EQ(cpp("-t*2"), "((-(t)) * (0x1p+1))");
    EXPECT_EQ(cpp("t/(t+1)"), "((t) / ((t) + (0x1p+0)))");
}

TEST(ExpressionCppSource, NamesFunctionsTheDeviceHas) {
    EXPECT_EQ(cpp("abs(t)"), "(fabs(t))");
    EXPECT_EQ(cpp("min(t, 1)"), "(deme_min((t), (0x1p+0)))");
    EXPECT_EQ(cpp("max(t, 1)"), "(deme_max((t), (0x1p+0)))");
    EXPECT_EQ(cpp("pow(t, 2)"), "(pow((t), (0x1p+1)))");
}

TEST(ExpressionCppSource, FoldedConstantsIncludingNonFiniteOnes) {
    EXPECT_EQ(cpp("2*pi"), "(" + std::string("0x1.921fb54442d18p+2") + ")");
    EXPECT_EQ(cpp("1/0"), "(1.0 / 0.0)");
    EXPECT_EQ(cpp("-1/0"), "(-1.0 / 0.0)");
    EXPECT_EQ(cpp("0/0"), "(0.0 / 0.0)");
    EXPECT_EQ(Expression().toCppSource({"t"}), "(0.0)");
}
