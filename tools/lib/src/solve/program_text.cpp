// A program's C++ text as the compile cache reads it: its tokens, and what at namespace or class
// scope could run before main (program_text.hpp).
#include "program_text.hpp"

#include <algorithm>
#include <set>

namespace helios::solve::detail {
namespace {

bool is_digit(char c) {
  return c >= '0' && c <= '9';
}
// A character of an identifier: ASCII letters, digits, '_', and any byte of a UTF-8 sequence.
bool is_word(char c) {
  return c == '_' || is_digit(c) || (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') ||
         static_cast<unsigned char>(c) >= 0x80;
}

// The punctuators of more than one character, longest first; a digraph maps to what it spells.
const std::vector<std::pair<std::string, std::string>>& punctuators() {
  static const std::vector<std::pair<std::string, std::string>> list = {
      {"%:%:", "##"}, {"<<=", "<<="}, {">>=", ">>="}, {"->*", "->*"}, {"...", "..."}, {"::", "::"}, {"->", "->"},
      {"++", "++"},   {"--", "--"},   {"<<", "<<"},   {">>", ">>"},   {"<=", "<="},   {">=", ">="}, {"==", "=="},
      {"!=", "!="},   {"&&", "&&"},   {"||", "||"},   {"+=", "+="},   {"-=", "-="},   {"*=", "*="}, {"/=", "/="},
      {"%=", "%="},   {"&=", "&="},   {"|=", "|="},   {"^=", "^="},   {".*", ".*"},   {"##", "##"}, {"<%", "{"},
      {"%>", "}"},    {"<:", "["},    {":>", "]"},    {"%:", "#"}};
  return list;
}

// The encoding prefixes of a string or character literal (R: raw).
bool is_literal_prefix(const std::string& word) {
  static const std::set<std::string> prefixes = {"u8", "u", "U", "L", "R", "u8R", "uR", "UR", "LR"};
  return prefixes.count(word) > 0;
}

class Reader {
 public:
  explicit Reader(const std::string& source) : s_(source) {}

  ProgramText read() {
    out_.tokens.reserve(s_.size() / 4);  // about one token in four characters of generated code
    out_.line_starts_in_code.push_back(true);
    if (s_.find("\\\n") != std::string::npos || s_.find("\\\r\n") != std::string::npos)
      return fail("a line ends in a backslash (a line splice)");
    bool line_start = true;  // nothing but white space since the line began
    while (i_ < s_.size() && out_.unreadable.empty()) {
      const char c = s_[i_];
      if (c == '\n') {
        new_line(true);
        ++i_;
        line_start = true;
      } else if (c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v') {
        ++i_;
      } else if (s_.compare(i_, 2, "//") == 0) {
        i_ = std::min(s_.find('\n', i_), s_.size());
      } else if (s_.compare(i_, 2, "/*") == 0) {
        block_comment();
      } else if (line_start && (c == '#' || s_.compare(i_, 2, "%:") == 0)) {
        directive();
      } else {
        line_start = false;
        token();
      }
    }
    return std::move(out_);
  }

 private:
  const std::string& s_;
  std::size_t i_ = 0, line_ = 1;
  ProgramText out_;

  ProgramText fail(const std::string& why) {
    out_.unreadable = why;
    return out_;
  }
  void stop(const std::string& why) {
    if (out_.unreadable.empty()) out_.unreadable = "line " + std::to_string(line_) + ": " + why;
  }
  void new_line(bool in_code) {
    ++line_;
    out_.line_starts_in_code.push_back(in_code);
  }
  // Moves past s_[from, to), counting its lines as not in code.
  void pass(std::size_t to) {
    for (; i_ < to; ++i_)
      if (s_[i_] == '\n') new_line(false);
  }

  void block_comment() {
    const std::size_t end = s_.find("*/", i_ + 2);
    if (end == std::string::npos) return stop("a comment is not closed");
    pass(end + 2);
  }

  // A preprocessor line: kept as its text (the cache decides which it allows).
  void directive() {
    const std::size_t end = std::min(s_.find('\n', i_), s_.size());
    std::string text = s_.substr(i_, end - i_);
    if (text.find("/*") != std::string::npos) return stop("a comment begins on a preprocessor line");
    while (!text.empty() && (text.back() == ' ' || text.back() == '\t' || text.back() == '\r')) text.pop_back();
    out_.directives.push_back(text);
    i_ = end;
  }

  void push(Token::Kind kind, std::string text, std::size_t line) {
    out_.tokens.push_back({kind, std::move(text), line});
  }

  void token() {
    const char c = s_[i_];
    const std::size_t start = i_, line = line_;
    if (c == '\\') return stop("a universal character name or a stray backslash in code");
    if (is_digit(c) || (c == '.' && i_ + 1 < s_.size() && is_digit(s_[i_ + 1]))) return number();
    if (is_word(c)) {
      while (i_ < s_.size() && is_word(s_[i_])) ++i_;
      const std::string word = s_.substr(start, i_ - start);
      if (i_ < s_.size() && (s_[i_] == '"' || s_[i_] == '\'') && is_literal_prefix(word))
        return literal(start, word.back() == 'R' && s_[i_] == '"');
      if (i_ < s_.size() && s_[i_] == '\\') return stop("a universal character name in an identifier");
      return push(Token::Kind::Identifier, word, line);
    }
    if (c == '"' || c == '\'') return literal(start, false);
    for (const auto& [spelling, meaning] : punctuators())
      if (s_.compare(i_, spelling.size(), spelling) == 0) {
        i_ += spelling.size();
        return push(Token::Kind::Punctuator, meaning, line);
      }
    ++i_;
    push(Token::Kind::Punctuator, std::string(1, c), line);
  }

  // A preprocessing number: digits, letters, '.', digit separators and exponent signs.
  void number() {
    const std::size_t start = i_;
    while (i_ < s_.size()) {
      const char c = s_[i_];
      if ((c == '+' || c == '-') && i_ > start && std::string("eEpP").find(s_[i_ - 1]) != std::string::npos) {
        ++i_;
      } else if (c == '\'' && i_ + 1 < s_.size() && is_word(s_[i_ + 1])) {
        i_ += 2;
      } else if (is_word(c) || c == '.') {
        ++i_;
      } else {
        break;
      }
    }
    push(Token::Kind::Number, s_.substr(start, i_ - start), line_);
  }

  // A string or character literal from `start` (its prefix included), s_[i_] its opening quote.
  void literal(std::size_t start, bool raw) {
    const std::size_t line = line_;
    if (raw) {
      const std::size_t open = s_.find('(', i_);
      if (open == std::string::npos || open - i_ > 17) return stop("a raw string without its delimiter");
      const std::string close = ")" + s_.substr(i_ + 1, open - i_ - 1) + "\"";
      const std::size_t end = s_.find(close, open);
      if (end == std::string::npos) return stop("a raw string is not closed");
      pass(end + close.size());
    } else {
      const char quote = s_[i_++];
      while (i_ < s_.size() && s_[i_] != quote) {
        if (s_[i_] == '\n') return stop("a literal is not closed on its line");
        i_ += s_[i_] == '\\' ? 2 : 1;
      }
      if (i_ >= s_.size()) return stop("a literal is not closed");
      ++i_;
    }
    push(Token::Kind::String, s_.substr(start, i_ - start), line);
  }
};

// ---- code before main ------------------------------------------------------------------------

bool is(const Token* t, const char* text) {
  return t != nullptr && t->text == text;
}

// Tokens that make a declaration run code, or place it, where the reader cannot see: attributes
// (a constructor attribute runs a function before main), inline assembly, _Pragma.
bool hidden_code(const Token& t) {
  static const std::set<std::string> words = {"__attribute__", "__attribute", "__declspec", "asm",
                                              "__asm__",       "__asm",       "_Pragma",    "thread_local"};
  return t.kind == Token::Kind::Identifier && words.count(t.text) > 0;
}

// One declaration at namespace or class scope, as its tokens (a skipped body as "{" "}" with what
// it held, so an initializer's braces keep their content).
struct Declaration {
  std::vector<const Token*> tokens;
  bool class_body = false;  // it defines a class (or enum); `after` holds what follows its body
  std::size_t after = 0;

  // The index of the first token at depth 0 that is one of `texts`, else size().
  std::size_t first_at_depth0(const std::set<std::string>& texts) const {
    int depth = 0;
    for (std::size_t k = 0; k < tokens.size(); ++k) {
      const std::string& t = tokens[k]->text;
      if (depth == 0 && texts.count(t)) return k;
      if (t == "(" || t == "[" || t == "{") ++depth;
      if (t == ")" || t == "]" || t == "}") --depth;
    }
    return tokens.size();
  }
  bool has_at_depth0(const char* text) const { return first_at_depth0({text}) < tokens.size(); }
  bool head_has(const char* word, std::size_t head_end) const {
    for (std::size_t k = 0; k < head_end && k < tokens.size(); ++k)
      if (tokens[k]->text == word) return true;
    return false;
  }
  std::string text() const {
    std::string out;
    for (std::size_t k = 0; k < tokens.size() && out.size() < 80; ++k)
      out += (out.empty() ? "" : " ") + tokens[k]->text;
    return out.size() < 80 ? out : out.substr(0, 77) + "...";
  }
};

class Scanner {
 public:
  explicit Scanner(const std::vector<Token>& tokens) : t_(tokens) {}

  std::string run() {
    std::vector<bool> class_scope = {false};  // the scopes open: namespaces and classes
    std::vector<Declaration> outer;           // a class's declaration while its body is read
    Declaration d;
    for (std::size_t k = 0; k < t_.size() && why_.empty(); ++k) {
      const Token& t = t_[k];
      if (hidden_code(t) || (is(&t, "[") && k + 1 < t_.size() && is(&t_[k + 1], "["))) {
        refuse(t.line, "'" + t.text + (t.text == "[" ? "[" : "") + "' at namespace or class scope");
        break;
      }
      if (class_scope.back() && d.tokens.empty() &&
          (t.text == "public" || t.text == "private" || t.text == "protected") && k + 1 < t_.size() &&
          is(&t_[k + 1], ":")) {
        ++k;
        continue;
      }
      if (t.text == "(" || t.text == "[") {
        k = skip(k, t.text == "(" ? ")" : "]", d);
      } else if (t.text == "{") {
        const Open kind = opening(d, class_scope.back());
        if (kind == Open::Scope) {
          class_scope.push_back(false);
          d = Declaration();
        } else if (kind == Open::Class) {
          class_scope.push_back(true);
          outer.push_back(d);
          d = Declaration();
        } else if (kind == Open::Function) {
          k = skip(k, "}", d);
          d = Declaration();  // a function definition: its body runs when it is called
        } else {
          k = skip(k, "}", d);  // an initializer's braces, an enum's enumerators: part of the declaration
          if (kind == Open::Enum) {
            d.class_body = true;
            d.after = d.tokens.size();
          }
        }
      } else if (t.text == "}") {
        if (class_scope.size() == 1 || !d.tokens.empty()) {
          refuse(t.line, "a '}' the reader cannot place");
          break;
        }
        const bool was_class = class_scope.back();
        class_scope.pop_back();
        if (was_class) {
          d = outer.back();
          outer.pop_back();
          d.class_body = true;
          d.after = d.tokens.size();
        }
      } else if (t.text == ";") {
        check(d, class_scope.back(), t.line);
        d = Declaration();
      } else {
        d.tokens.push_back(&t);
      }
    }
    if (why_.empty() && (!d.tokens.empty() || class_scope.size() != 1))
      refuse(t_.empty() ? 0 : t_.back().line, "the text ends inside a declaration or a scope");
    return why_;
  }

 private:
  enum class Open { Scope, Class, Function, Enum, Initializer };
  const std::vector<Token>& t_;
  std::string why_;

  void refuse(std::size_t line, const std::string& what) {
    if (why_.empty()) why_ = "line " + std::to_string(line) + ": " + what;
  }

  // Appends t_[from] up to its matching `close` (the same kind of bracket) to d; returns its index.
  std::size_t skip(std::size_t from, const char* close, Declaration& d) {
    const std::string open = t_[from].text;
    int depth = 0;
    for (std::size_t k = from; k < t_.size(); ++k) {
      if (t_[k].text == open) ++depth;
      if (t_[k].text == close && --depth == 0) {
        for (std::size_t j = from; j <= k; ++j) d.tokens.push_back(&t_[j]);
        return k;
      }
    }
    refuse(t_[from].line, "a '" + open + "' is not closed");
    return t_.size();
  }

  // What a '{' opens after the declaration d so far.
  Open opening(const Declaration& d, bool in_class) const {
    const auto& v = d.tokens;
    if (!in_class && !v.empty() &&
        (is(v[0], "namespace") || (is(v[0], "inline") && v.size() > 1 && is(v[1], "namespace"))))
      return Open::Scope;
    if (!in_class && v.size() == 2 && is(v[0], "extern") && v[1]->kind == Token::Kind::String) return Open::Scope;
    if (d.has_at_depth0("=")) return Open::Initializer;
    if (d.has_at_depth0("enum")) return Open::Enum;
    if (d.has_at_depth0("(")) {
      // A function's body follows its parameters and qualifiers, or a trailing return type.
      static const std::set<std::string> qualifiers = {")",     "const",    "noexcept", "override",
                                                       "final", "volatile", "&",        "&&"};
      if (!v.empty() && (qualifiers.count(v.back()->text) || d.has_at_depth0("->"))) return Open::Function;
      return Open::Initializer;
    }
    if (d.has_at_depth0("struct") || d.has_at_depth0("class") || d.has_at_depth0("union")) return Open::Class;
    return Open::Initializer;  // a variable's braces: double k{...}
  }

  // A declaration that ended with ';' at namespace scope (in_class false) or in a class body.
  void check(const Declaration& d, bool in_class, std::size_t line) {
    const auto& v = d.tokens;
    if (v.empty()) return;
    static const std::set<std::string> harmless = {"using", "typedef", "static_assert", "namespace", "friend"};
    if (harmless.count(v[0]->text) ||
        (is(v[0], "template") && !d.has_at_depth0("=") && !d.class_body && !initialized_by_braces(d)))
      return;
    if (d.class_body) {
      if (d.after == v.size()) return;  // struct S {...};
      return refuse(line, "'" + d.text() + "' defines a variable of a class type");
    }
    const std::size_t head = d.first_at_depth0({"=", "(", "{"});
    if (d.head_has("constexpr", head)) return;  // constant initialization, or the compiler refuses it
    if (in_class) {
      if (!d.head_has("static", head)) return;  // a member: initialized when an object is made
      if (d.head_has("inline", head) || (head < v.size() && !is(v[head], "(")))
        return refuse(line, "'" + d.text() + "' is a static member initialized before main");
      return;
    }
    if (is(v[0], "extern") && head == v.size()) return;  // a declaration of something defined elsewhere
    if (v.size() == 4 && is(v[0], "HELIOS_MODULE_TABLE") && is(v[1], "(") && is(v[3], ")")) return;
    if (head < v.size() && is(v[head], "=") && literals_only(v, head + 1)) return;
    if (head < v.size() && is(v[head], "=") && runtime_record(d, head)) return;
    refuse(line, "'" + d.text() + "' is " +
                     (head < v.size() && is(v[head], "(") && !d.has_at_depth0("=")
                          ? "a declaration the reader cannot tell from a variable initialized before main"
                          : "a variable initialized before main, at static initialisation"));
  }

  static bool initialized_by_braces(const Declaration& d) { return !d.tokens.empty() && is(d.tokens.back(), "}"); }

  // An initializer of literals only (numbers, strings, true, false, nullptr) and arithmetic: it
  // reads nothing and calls nothing.
  static bool literals_only(const std::vector<const Token*>& v, std::size_t from) {
    static const std::set<std::string> allowed = {"{", "}", ",", "(",    ")",     "+",
                                                  "-", "*", "/", "true", "false", "nullptr"};
    for (std::size_t k = from; k < v.size(); ++k)
      if (v[k]->kind != Token::Kind::Number && v[k]->kind != Token::Kind::String && !allowed.count(v[k]->text))
        return false;
    return from < v.size();
  }

  // A record of the runtime whose numbers are references and pointers (runtime_records.hpp:
  // ProblemShape, OrbitBody) of names, strings, whole numbers and nullptr, as the PROBLEM block
  // writes kProblem and kOrbitBodies: the names are bound, not read.
  static bool runtime_record(const Declaration& d, std::size_t head) {
    const auto& v = d.tokens;
    std::size_t name = head;
    while (name > 0 && (is(v[name - 1], "[") || is(v[name - 1], "]"))) --name;
    if (name < 2 || (!is(v[name - 2], "ProblemShape") && !is(v[name - 2], "OrbitBody"))) return false;
    static const std::set<std::string> allowed = {"{", "}", ",", "::", "nullptr"};
    for (std::size_t k = head + 1; k < v.size(); ++k)
      if (v[k]->kind != Token::Kind::Identifier && v[k]->kind != Token::Kind::String && !allowed.count(v[k]->text) &&
          !(v[k]->kind == Token::Kind::Number && v[k]->text.find_first_not_of("0123456789") == std::string::npos))
        return false;
    return true;
  }
};

}  // namespace

ProgramText read_program_text(const std::string& source) {
  return Reader(source).read();
}

std::string code_before_main(const std::vector<Token>& tokens) {
  return Scanner(tokens).run();
}

}  // namespace helios::solve::detail
