// Recursive-descent parser that emits postfix bytecode directly, plus a switch-based stack evaluator.
// See Expression.h for the accepted language.
#include "codegen/Expression.h"

#include <deme/Error.h>
#include <deme/VariableTypes.h>

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdio>

namespace deme {

namespace {

// Captureless lambdas rather than &std::sin: the standard functions are overloaded and taking their
// address is not portable.
struct Function {
    const char* name;
    const char* cppName;  // what generated C++ calls (toCppSource)
    int arity;
    double (*fn1)(double);
    double (*fn2)(double, double);
};

const Function kFunctions[] = {
    {"sin", "sin", 1, [](double x) { return std::sin(x); }, nullptr},
    {"cos", "cos", 1, [](double x) { return std::cos(x); }, nullptr},
    {"tan", "tan", 1, [](double x) { return std::tan(x); }, nullptr},
    {"asin", "asin", 1, [](double x) { return std::asin(x); }, nullptr},
    {"acos", "acos", 1, [](double x) { return std::acos(x); }, nullptr},
    {"atan", "atan", 1, [](double x) { return std::atan(x); }, nullptr},
    {"sinh", "sinh", 1, [](double x) { return std::sinh(x); }, nullptr},
    {"cosh", "cosh", 1, [](double x) { return std::cosh(x); }, nullptr},
    {"tanh", "tanh", 1, [](double x) { return std::tanh(x); }, nullptr},
    {"exp", "exp", 1, [](double x) { return std::exp(x); }, nullptr},
    {"log", "log", 1, [](double x) { return std::log(x); }, nullptr},
    {"log10", "log10", 1, [](double x) { return std::log10(x); }, nullptr},
    {"sqrt", "sqrt", 1, [](double x) { return std::sqrt(x); }, nullptr},
    {"abs", "fabs", 1, [](double x) { return std::fabs(x); }, nullptr},
    {"fabs", "fabs", 1, [](double x) { return std::fabs(x); }, nullptr},
    {"floor", "floor", 1, [](double x) { return std::floor(x); }, nullptr},
    {"ceil", "ceil", 1, [](double x) { return std::ceil(x); }, nullptr},
    {"atan2", "atan2", 2, nullptr, [](double y, double x) { return std::atan2(y, x); }},
    {"pow", "pow", 2, nullptr, [](double x, double y) { return std::pow(x, y); }},
    {"fmin", "fmin", 2, nullptr, [](double x, double y) { return std::fmin(x, y); }},
    {"fmax", "fmax", 2, nullptr, [](double x, double y) { return std::fmax(x, y); }},
    // std::min/std::max semantics (not fmin/fmax) so NaN behaves as it would in the user's C++.
    {"min", "deme_min", 2, nullptr, [](double x, double y) { return std::min(x, y); }},
    {"max", "deme_max", 2, nullptr, [](double x, double y) { return std::max(x, y); }},
    {"fmod", "fmod", 2, nullptr, [](double x, double y) { return std::fmod(x, y); }},
};

bool isIdentStart(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool isIdentChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }
bool isDigit(char c) { return c >= '0' && c <= '9'; }

using Op = Expression::Op;

// Applies a non-leaf instruction to its operands; shared by constant folding and evaluate().
inline double apply(const Op& op, double a, double b) {
    switch (op.code) {
        case Op::Neg:
            return -a;
        case Op::Add:
            return a + b;
        case Op::Sub:
            return a - b;
        case Op::Mul:
            return a * b;
        case Op::Div:
            return a / b;
        case Op::Fn1:
            return op.fn1(a);
        case Op::Fn2:
            return op.fn2(a, b);
        case Op::Not:
            return a == 0.0 ? 1.0 : 0.0;
        case Op::Lt:
            return a < b ? 1.0 : 0.0;
        case Op::Le:
            return a <= b ? 1.0 : 0.0;
        case Op::Gt:
            return a > b ? 1.0 : 0.0;
        case Op::Ge:
            return a >= b ? 1.0 : 0.0;
        case Op::Eq:
            return a == b ? 1.0 : 0.0;
        case Op::Ne:
            return a != b ? 1.0 : 0.0;
        case Op::And:
            return (a != 0.0 && b != 0.0) ? 1.0 : 0.0;
        case Op::Or:
            return (a != 0.0 || b != 0.0) ? 1.0 : 0.0;
        default:
            return 0.0;  // leaves are handled by the callers
    }
}

class Parser {
  public:
    Parser(const std::string& text, const std::vector<std::string>& vars, const std::string& call, bool condition)
        : s_(text), vars_(vars), call_(call), condition_(condition) {}

    std::vector<Op> run() {
        skipWs();
        if (pos_ == s_.size()) fail(0, "the expression is empty");
        if (condition_)
            disjunction();
        else
            expr();
        if (pos_ != s_.size())
            fail(pos_, std::string("expected an operator (+ - * /") + (condition_ ? " < <= > >= == != && ||" : "") +
                           ") or the end, found " + found());
        return std::move(code_);
    }

  private:
    const std::string& s_;
    const std::vector<std::string>& vars_;
    const std::string& call_;
    const bool condition_;  // comparisons and logic allowed (parseCondition)
    size_t pos_ = 0;
    int depth_ = 0;    // values the code emitted so far leaves on the evaluation stack
    int nesting_ = 0;  // recursion guard, so "((((...1" cannot overflow the C++ stack
    std::vector<Op> code_;

    [[noreturn]] void fail(size_t at, const std::string& what) const {
        throwError(call_, "in expression \"" + s_ + "\" at position " + std::to_string(at + 1) + ": " + what);
    }
    void skipWs() {
        while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    }
    char peek() const { return pos_ < s_.size() ? s_[pos_] : '\0'; }
    std::string found() const {
        if (pos_ >= s_.size()) return "the end of the expression";
        if (s_[pos_] == '^')  // common mistake from other languages; fail with the fix, not "unexpected"
            fail(pos_, "'^' is not a power operator in C++ (it is bitwise XOR); use pow(a, b) instead");
        return std::string("'") + s_[pos_] + "'";
    }
    void expect(char c, const char* what) {
        skipWs();
        if (peek() != c) fail(pos_, std::string("expected ") + what + ", found " + found());
        ++pos_;
    }

    // Emits one instruction, folding it into a Const when all its operands are constants. In postfix
    // code a Const is a whole subexpression, so trailing Consts are exactly this op's operands.
    void emit(Op op) {
        const int nIn = (op.code == Op::Const || op.code == Op::Var)                     ? 0
                        : (op.code == Op::Neg || op.code == Op::Fn1 || op.code == Op::Not) ? 1
                                                                                           : 2;
        depth_ += 1 - nIn;  // pops nIn values, pushes one (folded or not)
        if (depth_ > Expression::kMaxStack) fail(pos_, "the expression is too complex to evaluate");
        const size_t n = code_.size();
        if (nIn > 0 && code_[n - 1].code == Op::Const && (nIn == 1 || code_[n - 2].code == Op::Const)) {
            const double v =
                nIn == 1 ? apply(op, code_[n - 1].value, 0.0) : apply(op, code_[n - 2].value, code_[n - 1].value);
            code_.resize(n - nIn);
            op = Op{Op::Const};
            op.value = v;
        }
        code_.push_back(op);
    }

    // Conditions only: || below &&, below !, below one comparison of two values.
    bool at(const char* tok) const { return s_.compare(pos_, std::char_traits<char>::length(tok), tok) == 0; }
    void disjunction() {
        conjunction();
        for (skipWs(); at("||"); skipWs()) {
            pos_ += 2;
            conjunction();
            emit(Op{Op::Or});
        }
    }
    void conjunction() {
        negation();
        for (skipWs(); at("&&"); skipWs()) {
            pos_ += 2;
            negation();
            emit(Op{Op::And});
        }
    }
    void negation() {
        skipWs();
        if (++nesting_ > 200) fail(pos_, "the expression is nested too deeply");
        if (peek() == '!' && !at("!=")) {
            ++pos_;
            negation();
            emit(Op{Op::Not});
        } else {
            comparison();
        }
        --nesting_;
    }
    void comparison() {
        expr();
        skipWs();
        static const struct {
            const char* tok;
            Op::Code code;
        } kCmp[] = {{"<=", Op::Le}, {">=", Op::Ge}, {"==", Op::Eq}, {"!=", Op::Ne}, {"<", Op::Lt}, {">", Op::Gt}};
        for (const auto& c : kCmp)
            if (at(c.tok)) {
                pos_ += std::char_traits<char>::length(c.tok);
                expr();
                emit(Op{c.code});
                return;
            }
    }

    void expr() {
        term();
        for (skipWs(); peek() == '+' || peek() == '-'; skipWs()) {
            const char c = s_[pos_++];
            term();
            emit(Op{c == '+' ? Op::Add : Op::Sub});
        }
    }
    void term() {
        unary();
        for (skipWs(); peek() == '*' || peek() == '/'; skipWs()) {
            const char c = s_[pos_++];
            unary();
            emit(Op{c == '*' ? Op::Mul : Op::Div});
        }
    }
    void unary() {
        skipWs();
        if (++nesting_ > 200) fail(pos_, "the expression is nested too deeply");
        if (peek() == '+' || peek() == '-') {
            const char c = s_[pos_++];
            unary();
            if (c == '-') emit(Op{Op::Neg});
        } else {
            primary();
        }
        --nesting_;
    }
    void primary() {
        skipWs();
        const char c = peek();
        if (isDigit(c) || (c == '.' && isDigit(pos_ + 1 < s_.size() ? s_[pos_ + 1] : '\0'))) return number();
        if (isIdentStart(c)) return identifier();
        if (c == '(') {
            ++pos_;
            if (condition_)
                disjunction();
            else
                expr();
            expect(')', "')'");
            return;
        }
        fail(pos_, "expected a number, variable, function or '(', found " + found());
    }

    // Scans the literal ourselves (so "1e" or "1.5ff" give exact positions) and converts it with
    // from_chars, which unlike strtod ignores the locale's decimal separator.
    void number() {
        const size_t start = pos_;
        while (isDigit(peek())) ++pos_;
        if (peek() == '.') ++pos_;
        while (isDigit(peek())) ++pos_;
        if (peek() == 'e' || peek() == 'E') {
            ++pos_;
            if (peek() == '+' || peek() == '-') ++pos_;
            if (!isDigit(peek())) fail(pos_, "expected digits in the exponent of a number, found " + found());
            while (isDigit(peek())) ++pos_;
        }
        Op op{Op::Const};
        // The scan above admits only valid syntax, so the one possible failure is overflow/underflow.
        if (std::from_chars(s_.data() + start, s_.data() + pos_, op.value).ec != std::errc())
            fail(start, "number " + s_.substr(start, pos_ - start) + " is out of the range of double");
        if (peek() == 'f' || peek() == 'F') ++pos_;  // C++ float suffix: ignored
        if (isIdentChar(peek()) || peek() == '.') fail(pos_, "malformed number");
        emit(op);
    }

    void identifier() {
        const size_t start = pos_;
        while (isIdentChar(peek()) || (peek() == ':' && pos_ + 1 < s_.size() && s_[pos_ + 1] == ':'))
            pos_ += peek() == ':' ? 2 : 1;
        const std::string name = s_.substr(start, pos_ - start);
        skipWs();
        const bool call = peek() == '(';

        for (size_t i = 0; i < vars_.size(); ++i)
            if (vars_[i] == name) {
                if (call) fail(start, "'" + name + "' is a variable, not a function");
                Op op{Op::Var};
                op.var = uint32_t(i);
                return emit(op);
            }
        if (name == "pi" || name == "PI" || name == "M_PI" || name == "deme::PI") {
            if (call) fail(start, "'" + name + "' is a constant, not a function");
            Op op{Op::Const};
            op.value = PI;
            return emit(op);
        }
        const std::string fname = name.compare(0, 5, "std::") == 0 ? name.substr(5) : name;
        const Function* f = nullptr;
        for (const Function& g : kFunctions)
            if (fname == g.name) f = &g;
        if (!f) {
            std::string known;
            for (const std::string& v : vars_) known += (known.empty() ? "" : ", ") + v;
            fail(start, "unknown " + std::string(call ? "function" : "name") + " '" + name +
                            "' (variables: " + (known.empty() ? "none" : known) + "; constants: pi)");
        }
        if (!call) fail(start, "function '" + name + "' must be called with arguments in parentheses");

        ++pos_;  // '('
        int args = 0;
        skipWs();
        if (peek() != ')') {
            for (;; ++pos_) {  // each pass skips the ',' just read
                expr();
                ++args;
                skipWs();
                if (peek() != ',') break;
            }
        }
        expect(')', args ? "',' or ')'" : "an argument or ')'");
        if (args != f->arity)
            fail(start, "function '" + name + "' takes " + std::to_string(f->arity) + " argument" +
                            (f->arity == 1 ? "" : "s") + ", got " + std::to_string(args));
        Op op{f->arity == 1 ? Op::Fn1 : Op::Fn2};
        op.fn1 = f->fn1;
        op.fn2 = f->fn2;
        op.name = f->cppName;
        emit(op);
    }
};

}  // namespace

Expression Expression::parse(const std::string& text, const std::vector<std::string>& variables,
                             const std::string& call) {
    Expression e;
    e.code_ = Parser(text, variables, call, false).run();
    e.text_ = text;
    return e;
}

Expression Expression::parseCondition(const std::string& text, const std::vector<std::string>& variables,
                                      const std::string& call) {
    Expression e;
    e.code_ = Parser(text, variables, call, true).run();
    e.text_ = text;
    return e;
}

bool Expression::isConstant() const {
    return std::none_of(code_.begin(), code_.end(), [](const Op& op) { return op.code == Op::Var; });
}

double Expression::evaluate(const double* values) const {
    // Folding leaves constant expressions as a single Const, so this is the common fast path.
    if (code_.empty()) return 0.0;
    if (code_.size() == 1) return code_[0].code == Op::Var ? values[code_[0].var] : code_[0].value;
    double stack[kMaxStack];  // parse() guarantees the code never needs more
    int sp = 0;               // number of values on the stack
    for (const Op& op : code_) {
        switch (op.code) {
            case Op::Const:
                stack[sp++] = op.value;
                break;
            case Op::Var:
                stack[sp++] = values[op.var];
                break;
            case Op::Neg:
            case Op::Fn1:
            case Op::Not:
                stack[sp - 1] = apply(op, stack[sp - 1], 0.0);
                break;
            default:
                --sp;
                stack[sp - 1] = apply(op, stack[sp - 1], stack[sp]);
                break;
        }
    }
    return stack[0];
}

std::string Expression::toCppSource(const std::vector<std::string>& variables) const {
    if (code_.empty()) return "(0.0)";
    // Postfix to fully parenthesised infix, so no precedence question can arise.
    std::vector<std::string> stack;
    for (const Op& op : code_) {
        switch (op.code) {
            case Op::Const: {
                char buf[64];
                if (std::isnan(op.value))  // folded from e.g. 0/0: no literal spells these
                    std::snprintf(buf, sizeof buf, "(0.0 / 0.0)");
                else if (std::isinf(op.value))
                    std::snprintf(buf, sizeof buf, "(%s1.0 / 0.0)", op.value < 0 ? "-" : "");
                else
                    std::snprintf(buf, sizeof buf, "(%a)", op.value);  // hexadecimal: exact, round-trips
                stack.emplace_back(buf);
                break;
            }
            case Op::Var:
                stack.push_back("(" + variables.at(op.var) + ")");
                break;
            case Op::Neg:
                stack.back() = "(-" + stack.back() + ")";
                break;
            case Op::Fn1:
                stack.back() = std::string("(") + op.name + stack.back() + ")";
                break;
            case Op::Not:
                stack.back() = "((" + stack.back() + ") == 0.0 ? 1.0 : 0.0)";
                break;
            default: {
                const std::string b = stack.back();
                stack.pop_back();
                std::string& a = stack.back();
                if (op.code == Op::Fn2) {
                    a = std::string("(") + op.name + "(" + a + ", " + b + "))";
                } else if (op.code >= Op::Lt) {  // comparisons and logic: 1.0 or 0.0, as evaluate()
                    const Op::Code k = op.code;
                    const char* sym = k == Op::Lt ? " < " : k == Op::Le ? " <= " : k == Op::Gt ? " > " : k == Op::Ge ? " >= "
                                    : k == Op::Eq ? " == " : " != ";
                    if (k == Op::And || k == Op::Or)
                        a = "(((" + a + " != 0.0)" + (k == Op::And ? " && " : " || ") + "(" + b + " != 0.0)) ? 1.0 : 0.0)";
                    else
                        a = "((" + a + sym + b + ") ? 1.0 : 0.0)";
                } else {
                    const char* sym = op.code == Op::Add ? " + " : op.code == Op::Sub ? " - " : op.code == Op::Mul ? " * " : " / ";
                    a = "(" + a + sym + b + ")";
                }
                break;
            }
        }
    }
    return stack[0];
}

}  // namespace deme
