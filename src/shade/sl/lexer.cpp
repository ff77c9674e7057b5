#include "shade/sl/lexer.h"

#include <cctype>
#include <cstdlib>

namespace streyes::sl {

Lexer::Lexer(const std::string& source, std::shared_ptr<const std::string> file)
    : src_(source), file_(std::move(file)) {}

void Lexer::fail(const std::string& what) const { throw InputError(loc(line_, col_), what); }

char Lexer::advance() {
    char c = src_[pos_++];
    if (c == '\n') {
        ++line_;
        col_ = 1;
    } else {
        ++col_;
    }
    return c;
}

void Lexer::skipSpaceAndComments() {
    for (;;) {
        char c = peek();
        if (c == '\0') return;
        if (std::isspace(static_cast<unsigned char>(c))) {
            advance();
        } else if (c == '/' && peek(1) == '/') {
            while (peek() != '\n' && peek() != '\0') advance();
        } else if (c == '/' && peek(1) == '*') {
            int line = line_, col = col_;
            advance();
            advance();
            while (!(peek() == '*' && peek(1) == '/')) {
                if (peek() == '\0') throw InputError(loc(line, col), "unterminated comment");
                advance();
            }
            advance();
            advance();
        } else if (c == '#' && col_ == 1) {
            // No preprocessor: a #pragma (or a cpp line marker) is ignored, anything else is
            // refused rather than silently misread.
            size_t end = src_.find('\n', pos_);
            std::string directive = src_.substr(pos_, end == std::string::npos ? std::string::npos : end - pos_);
            if (directive.rfind("#pragma", 0) != 0 && directive.rfind("# ", 0) != 0 && directive.rfind("#line", 0) != 0)
                fail("preprocessor directives are not supported: '" + directive + "'");
            while (peek() != '\n' && peek() != '\0') advance();
        } else {
            return;
        }
    }
}

std::vector<Token> Lexer::tokenize() {
    std::vector<Token> out;
    for (;;) {
        skipSpaceAndComments();
        Token t;
        t.line = line_;
        t.column = col_;
        t.offset = pos_;
        char c = peek();
        if (c == '\0') {
            t.end = pos_;
            out.push_back(t);
            return out;
        }
        if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
            t.kind = TokenKind::Ident;
            while (std::isalnum(static_cast<unsigned char>(peek())) || peek() == '_') t.text += advance();
        } else if (std::isdigit(static_cast<unsigned char>(c)) ||
                   (c == '.' && std::isdigit(static_cast<unsigned char>(peek(1))))) {
            t.kind = TokenKind::Number;
            while (std::isdigit(static_cast<unsigned char>(peek()))) t.text += advance();
            if (peek() == '.') {
                t.text += advance();
                while (std::isdigit(static_cast<unsigned char>(peek()))) t.text += advance();
            }
            if ((peek() == 'e' || peek() == 'E') &&
                (std::isdigit(static_cast<unsigned char>(peek(1))) ||
                 ((peek(1) == '+' || peek(1) == '-') && std::isdigit(static_cast<unsigned char>(peek(2)))))) {
                t.text += advance();
                if (peek() == '+' || peek() == '-') t.text += advance();
                while (std::isdigit(static_cast<unsigned char>(peek()))) t.text += advance();
            }
            if (std::isalpha(static_cast<unsigned char>(peek())) || peek() == '_')
                fail(std::string("unexpected '") + peek() + "' after the number " + t.text);
            t.number = std::strtod(t.text.c_str(), nullptr);
        } else if (c == '"') {
            t.kind = TokenKind::String;
            advance();
            for (;;) {
                char d = peek();
                if (d == '\0' || d == '\n') throw InputError(loc(t.line, t.column), "unterminated string");
                advance();
                if (d == '"') break;
                if (d == '\\') {
                    char e = advance();
                    switch (e) {
                        case 'n': t.text += '\n'; break;
                        case 't': t.text += '\t'; break;
                        case 'r': t.text += '\r'; break;
                        case '\\': t.text += '\\'; break;
                        case '"': t.text += '"'; break;
                        default: t.text += '\\'; t.text += e; break;  // kept for format(): "\%"
                    }
                } else {
                    t.text += d;
                }
            }
        } else {
            t.kind = TokenKind::Punct;
            static const char* two[] = {"==", "!=", "<=", ">=", "&&", "||", "+=", "-=", "*=", "/=", "++", "--"};
            for (const char* p : two)
                if (c == p[0] && peek(1) == p[1]) t.text = p;
            if (t.text.empty()) {
                static const std::string one = "+-*/^.<>=!?:;,(){}[]";
                if (one.find(c) == std::string::npos) fail(std::string("unexpected character '") + c + "'");
                t.text = std::string(1, c);
            }
            for (size_t k = 0; k < t.text.size(); ++k) advance();
        }
        t.end = pos_;
        out.push_back(std::move(t));
    }
}

}  // namespace streyes::sl
