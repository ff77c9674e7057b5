#include "shade/sl/lexer.h"

#include <cctype>
#include <cstdlib>

namespace streyes::sl {

Lexer::Lexer(const PreprocessedSource& source) : pp_(source), src_(source.text) {}

void Lexer::fail(const std::string& what) const { throw InputError(pp_.locate(pos_), what); }

char Lexer::advance() { return src_[pos_++]; }

void Lexer::skipSpaceAndComments() {
    for (;;) {
        char c = peek();
        if (c == '\0') return;
        if (std::isspace(static_cast<unsigned char>(c))) {
            advance();
        } else if (c == '/' && peek(1) == '/') {
            while (peek() != '\n' && peek() != '\0') advance();
        } else if (c == '/' && peek(1) == '*') {
            const size_t start = pos_;
            advance();
            advance();
            while (!(peek() == '*' && peek(1) == '/')) {
                if (peek() == '\0') throw InputError(pp_.locate(start), "unterminated comment");
                advance();
            }
            advance();
            advance();
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
        t.loc = pp_.locate(pos_);
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
            t.number = std::strtod(t.text.c_str(), nullptr);
            // C's float suffix, as RenderMan's compilers accept it: 0.5f is 0.5.
            if ((peek() == 'f' || peek() == 'F') && !std::isalnum(static_cast<unsigned char>(peek(1))) && peek(1) != '_')
                advance();
            if (std::isalpha(static_cast<unsigned char>(peek())) || peek() == '_')
                fail(std::string("unexpected '") + peek() + "' after the number " + t.text);
        } else if (c == '"') {
            t.kind = TokenKind::String;
            advance();
            for (;;) {
                char d = peek();
                if (d == '\0' || d == '\n') throw InputError(t.loc, "unterminated string");
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
