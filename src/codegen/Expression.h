// A small compiler/evaluator for the C++-like math strings users give for prescribed motion,
// e.g. "0.1*sin(t)" or "-2*pi*cos(2*pi*t) + 0.5". The text is parsed once into postfix bytecode
// (constant subexpressions folded) and then evaluated every time step with no allocation.
//
// Grammar (standard C++ precedence, binary operators left-associative):
//   expr    := term (('+' | '-') term)*
//   term    := unary (('*' | '/') unary)*
//   unary   := ('+' | '-') unary | primary          -- so -2*3 is (-2)*3, as in C++
//   primary := number | variable | constant | function '(' expr (',' expr)* ')' | '(' expr ')'
// Numbers: 3  3.5  .5  1e-3  2.5E+2, with an optional trailing f/F (1.5f) that is ignored.
// Constants: pi, PI, M_PI, deme::PI. Functions (a "std::" prefix is accepted): sin cos tan asin acos
// atan sinh cosh tanh exp log log10 sqrt abs fabs floor ceil (one argument); atan2 pow fmin fmax
// min max fmod (two arguments). Whitespace may appear anywhere between tokens.
//
// Differences from C++ worth knowing:
//   - All arithmetic is done in double, so integer division does not truncate: 1/2 is 0.5 here.
//   - '^' is rejected with a hint to use pow(a, b) (in C++ it is bitwise XOR, never a power).
//   - No comparison, ternary, '%' or other operators in a value; a condition (parseCondition) adds
//     comparisons and logic below all of the above:
//       cond := conj ('||' conj)* ; conj := neg ('&&' neg)* ; neg := '!' neg | cmp
//       cmp  := expr (('<' | '<=' | '>' | '>=' | '==' | '!=') expr)?   -- true is 1, false 0
//     Both sides of && and || are evaluated (they have no side effects); a condition holds where
//     its value is not 0.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace deme {

class Expression {
  public:
    Expression() = default;  // evaluates to 0; text() is empty

    // Parses `text`; on any syntax error, unknown identifier/function, wrong argument count or empty
    // text, throws deme::Error via throwError(call, ...) with a message that quotes the text and
    // gives the 1-based character position of the problem. `variables` lists the allowed variable
    // names (e.g. {"t"}); their values are passed to evaluate() in that order.
    static Expression parse(const std::string& text, const std::vector<std::string>& variables,
                            const std::string& call);

    // A condition (see above), e.g. "Z < 0.1 && Vz < 0": its value is 1 where it holds, 0 where not.
    static Expression parseCondition(const std::string& text, const std::vector<std::string>& variables,
                                     const std::string& call);

    // values[i] is the value of variables[i]; may be null if isConstant().
    double evaluate(const double* values) const;
    bool isConstant() const;  // true if no variable is referenced
    const std::string& text() const { return text_; }

    // The same computation as C++ source (one parenthesised double expression), for code compiled at
    // run time (the GPU's prescription kernel): variables[i] is the source text that stands for
    // variable i, constants are written as exact hexadecimal literals, and min/max/abs are spelled
    // deme_min/deme_max/fabs (the caller defines deme_min/deme_max with std::min/max semantics).
    std::string toCppSource(const std::vector<std::string>& variables) const;

    // Deepest value stack any expression may need; deeper ones are rejected at parse time so that
    // evaluate() can use a fixed-size array on the C++ stack.
    static constexpr int kMaxStack = 64;

    // One postfix instruction. Public only so the .cpp's helpers can build it; not an API.
    struct Op {
        enum Code : uint8_t { Const, Var, Neg, Add, Sub, Mul, Div, Fn1, Fn2, Not, Lt, Le, Gt, Ge, Eq, Ne, And, Or } code;
        uint32_t var = 0;                         // Var: index into values
        double value = 0.0;                       // Const
        double (*fn1)(double) = nullptr;          // Fn1
        double (*fn2)(double, double) = nullptr;  // Fn2
        const char* name = nullptr;               // Fn1/Fn2: the C++ function to call in generated code
    };

  private:
    std::string text_;
    std::vector<Op> code_;  // empty means the constant 0 (default-constructed)
};

}  // namespace deme
