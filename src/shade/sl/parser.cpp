#include "shade/sl/parser.h"

#include <cmath>
#include <cstring>

namespace streyes::sl {

namespace {

const char* const kShaderTypes[] = {"surface", "displacement", "light", "volume", "imager"};
const char* const kTypeNames[] = {"float", "color", "point", "vector", "normal", "matrix", "string"};

bool isKeyword(const std::string& s) {
    static const char* const words[] = {
        "surface", "displacement", "light", "volume", "imager", "transformation", "float", "color", "point",
        "vector", "normal", "matrix", "string", "void", "uniform", "varying", "output", "extern", "if", "else",
        "while", "for", "break", "continue", "return", "illuminance", "illuminate", "solar"};
    for (const char* w : words)
        if (s == w) return true;
    return false;
}

}  // namespace

Module parseShader(const PreprocessedSource& source) {
    Lexer lexer(source);
    Parser parser(lexer.tokenize(), source.text);
    return parser.parseModule();
}

Parser::Parser(std::vector<Token> tokens, const std::string& source) : toks_(std::move(tokens)), source_(source) {}

const Token& Parser::peek(int k) const {
    size_t i = pos_ + size_t(k);
    return i < toks_.size() ? toks_[i] : toks_.back();
}

Token Parser::next() {
    Token t = peek();
    if (pos_ < toks_.size() - 1) ++pos_;
    return t;
}

bool Parser::isPunct(const char* p, int k) const {
    const Token& t = peek(k);
    return t.kind == TokenKind::Punct && t.text == p;
}

bool Parser::isIdent(const char* name, int k) const {
    const Token& t = peek(k);
    return t.kind == TokenKind::Ident && t.text == name;
}

bool Parser::accept(const char* p) {
    if (!isPunct(p)) return false;
    next();
    return true;
}

void Parser::fail(const Token& at, const std::string& what) const {
    std::string found;
    switch (at.kind) {
        case TokenKind::End: found = "the end of the file"; break;
        case TokenKind::String: found = "\"" + at.text + "\""; break;
        default: found = "'" + at.text + "'"; break;
    }
    throw InputError(locOf(at), what + ", found " + found);
}

void Parser::expect(const char* p, const char* what) {
    if (!accept(p)) fail(peek(), std::string("expected '") + p + "' " + what);
}

std::string Parser::expectIdent(const char* what) {
    const Token& t = peek();
    if (t.kind != TokenKind::Ident || isKeyword(t.text)) fail(t, std::string("expected ") + what);
    return next().text;
}

std::string Parser::textBetween(const Token& first, const Token& afterLast) const {
    if (afterLast.offset <= first.offset) return "";
    std::string s = source_.substr(first.offset, afterLast.offset - first.offset);
    while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.pop_back();
    return s;
}

bool Parser::atTypeName(int k) const {
    if (peek(k).kind != TokenKind::Ident) return false;
    for (const char* n : kTypeNames)
        if (peek(k).text == n) return true;
    return false;
}

BaseType Parser::parseBaseType() {
    Token t = next();
    static const BaseType types[] = {BaseType::Float, BaseType::Color, BaseType::Point, BaseType::Vector,
                                     BaseType::Normal, BaseType::Matrix, BaseType::String};
    for (size_t i = 0; i < 7; ++i)
        if (t.text == kTypeNames[i]) return types[i];
    if (t.text == "void") return BaseType::Void;
    fail(t, "expected a type");
}

// ---- Definitions --------------------------------------------------------------------------------

Module Parser::parseModule() {
    Module m;
    while (peek().kind != TokenKind::End) {
        bool shader = false;
        for (const char* s : kShaderTypes)
            if (isIdent(s) && peek(1).kind == TokenKind::Ident) shader = true;
        if (isIdent("transformation") && peek(1).kind == TokenKind::Ident)
            fail(peek(), "transformation shaders are not supported");
        if (shader) {
            if (m.shader) fail(peek(), "a second shader in one file (one shader per file)");
            parseShaderDef(m);
        } else {
            parseFunction(m);
        }
    }
    if (!m.shader) throw InputError(locOf(peek()), "no shader defined (expected surface, displacement, light, volume or imager)");
    return m;
}

void Parser::parseShaderDef(Module& m) {
    auto s = std::make_unique<ShaderDef>();
    Token kind = next();
    s->loc = locOf(kind);
    const ShaderType types[] = {ShaderType::Surface, ShaderType::Displacement, ShaderType::Light, ShaderType::Volume,
                                ShaderType::Imager};
    for (size_t i = 0; i < 5; ++i)
        if (kind.text == kShaderTypes[i]) s->type = types[i];
    s->name = expectIdent("the shader's name");
    expect("(", "after the shader's name");
    s->formals = parseFormals();
    for (VarDecl& d : s->formals)
        for (Declarator& dc : d.decls)
            if (!dc.init) throw InputError(dc.loc, "shader parameter '" + dc.name + "' needs a default value");
    s->body = parseBlock();
    m.shader = std::move(s);
}

void Parser::parseFunction(Module& m) {
    auto f = std::make_unique<FunctionDef>();
    f->loc = locOf(peek());
    if (atTypeName() || isIdent("void")) {
        f->returnType = SlType(parseBaseType());
    } else if (peek().kind != TokenKind::Ident || !isPunct("(", 1)) {
        fail(peek(), "expected a shader or function definition");
    }
    f->loc = locOf(peek());
    f->name = expectIdent("a function name");
    expect("(", "after the function's name");
    f->formals = parseFormals();
    f->body = parseBlock();
    m.functions.push_back(std::move(f));
}

// formals: [output] [uniform|varying] type name [= default], ...; ... )
std::vector<VarDecl> Parser::parseFormals() {
    std::vector<VarDecl> out;
    while (!accept(")")) {
        VarDecl d = parseDeclHead(true);
        parseDeclarators(d);
        out.push_back(std::move(d));
        if (accept(";")) continue;
        if (isPunct(")")) continue;
        fail(peek(), "expected ';' or ')' after a parameter");
    }
    return out;
}

VarDecl Parser::parseDeclHead(bool formal) {
    VarDecl d;
    d.loc = locOf(peek());
    for (;;) {
        if (isIdent("output")) {
            if (!formal) fail(peek(), "'output' is only for parameters");
            next();
            d.output = true;
        } else if (isIdent("extern")) {
            if (formal) fail(peek(), "'extern' is not for parameters");
            next();
            d.isExtern = true;
        } else if (isIdent("uniform") || isIdent("varying")) {
            if (d.hasDetail) fail(peek(), "a second storage class");
            d.hasDetail = true;
            d.detail = next().text == "uniform" ? Detail::Uniform : Detail::Varying;
        } else {
            break;
        }
    }
    if (!atTypeName()) fail(peek(), "expected a type");
    d.base = parseBaseType();
    return d;
}

void Parser::parseDeclarators(VarDecl& d) {
    do {
        Declarator dc;
        dc.loc = locOf(peek());
        dc.name = expectIdent("a name");
        bool unsized = false;
        if (accept("[")) {
            const Token& n = peek();
            if (isPunct("]")) {
                unsized = true;  // float a[] = {...}: the initialiser's length
            } else {
                if (n.kind != TokenKind::Number || n.number < 1 || n.number != std::floor(n.number))
                    fail(n, "expected a positive whole array length");
                dc.arrayLen = int(next().number);
            }
            expect("]", "after the array length");
        }
        if (accept("=")) {
            const Token& first = peek();
            dc.init = isPunct("{") ? parseArrayInit() : parseAssign();
            dc.initText = textBetween(first, peek());
        }
        if (unsized) {
            // Resizable (PRMan's RSL 2): a parameter sized by its value, a local that resize,
            // push and pop change, a function's formal taking an array of any length (string
            // arrays too).
            dc.arrayLen = SlType::kResizable;
        }
        d.decls.push_back(std::move(dc));
        // In formals a ',' may also separate declarators of one type (float a, b).
    } while (accept(","));
}

ExprPtr Parser::parseArrayInit() {
    auto e = std::make_unique<Expr>(ExprKind::ArrayInit, locOf(peek()));
    expect("{", "to start an array initialiser");
    if (!isPunct("}")) {
        do {
            e->args.push_back(parseAssign());
        } while (accept(","));
    }
    expect("}", "to end an array initialiser");
    return e;
}

// ---- Statements ---------------------------------------------------------------------------------

bool Parser::atDeclStart() const {
    if (isIdent("extern") || isIdent("uniform") || isIdent("varying")) return true;
    return atTypeName() && peek(1).kind == TokenKind::Ident;
}

StmtPtr Parser::parseBlock() {
    auto b = std::make_unique<Stmt>(StmtKind::Block, locOf(peek()));
    expect("{", "to start a block");
    while (!accept("}")) {
        if (peek().kind == TokenKind::End) fail(peek(), "expected '}' to end the block");
        b->body.push_back(parseStatement());
    }
    return b;
}

StmtPtr Parser::parseStatement() {
    const Token& t = peek();
    SourceLoc loc = locOf(t);
    if (isPunct("{")) return parseBlock();
    if (accept(";")) return std::make_unique<Stmt>(StmtKind::Empty, loc);
    if (t.kind == TokenKind::Ident) {
        if (t.text == "if") return parseIf();
        if (t.text == "while") {
            next();
            auto s = std::make_unique<Stmt>(StmtKind::While, loc);
            expect("(", "after 'while'");
            s->expr = parseExpr();
            expect(")", "after the loop's condition");
            s->body.push_back(parseStatement());
            return s;
        }
        if (t.text == "for") {
            next();
            auto s = std::make_unique<Stmt>(StmtKind::For, loc);
            expect("(", "after 'for'");
            if (!isPunct(";")) s->init = parseExpr();
            expect(";", "after the loop's start");
            if (!isPunct(";")) s->expr = parseExpr();
            expect(";", "after the loop's condition");
            if (!isPunct(")")) s->step = parseExpr();
            expect(")", "after the loop's step");
            s->body.push_back(parseStatement());
            return s;
        }
        if (t.text == "break" || t.text == "continue") {
            auto s = std::make_unique<Stmt>(t.text == "break" ? StmtKind::Break : StmtKind::Continue, loc);
            next();
            if (peek().kind == TokenKind::Number) {
                const Token& n = peek();
                if (n.number < 1 || n.number != std::floor(n.number)) fail(n, "expected a loop count");
                s->level = int(next().number);
            }
            expect(";", "after break or continue");
            return s;
        }
        if (t.text == "return") {
            next();
            auto s = std::make_unique<Stmt>(StmtKind::Return, loc);
            if (!isPunct(";")) s->expr = parseExpr();
            expect(";", "after the returned value");
            return s;
        }
        if (t.text == "gather" && isPunct("(", 1)) return parseGather();
        if (t.text == "illuminance") return parseLightStatement(StmtKind::Illuminance);
        if (t.text == "illuminate") return parseLightStatement(StmtKind::Illuminate);
        if (t.text == "solar") return parseLightStatement(StmtKind::Solar);
        if (t.text == "else") fail(t, "'else' without 'if'");
        if ((atTypeName() || t.text == "void") && peek(1).kind == TokenKind::Ident && isPunct("(", 2))
            fail(t, "functions cannot be defined inside other functions or shaders");
        if (atDeclStart()) {
            auto s = std::make_unique<Stmt>(StmtKind::Decl, loc);
            s->decl = parseDeclHead(false);
            parseDeclarators(s->decl);
            expect(";", "after the declaration");
            return s;
        }
    }
    auto s = std::make_unique<Stmt>(StmtKind::Expr, loc);
    s->expr = parseExpr();
    expect(";", "after the expression");
    return s;
}

StmtPtr Parser::parseIf() {
    auto s = std::make_unique<Stmt>(StmtKind::If, locOf(next()));
    expect("(", "after 'if'");
    s->expr = parseExpr();
    expect(")", "after the condition");
    s->body.push_back(parseStatement());
    if (isIdent("else")) {
        next();
        s->body.push_back(parseStatement());
    }
    return s;
}

// gather(category, P, dir, angle, samples, "surface:Ci", var, ..., options...) stmt [else stmt]
// (PRMan's): a loop over the samples, each tracing one ray a point, the first statement where it
// hits, the second where it misses. Written as the loop it is, with names no shader can spell:
//   { uniform float gather$nK = samples, gather$iK;
//     for (gather$iK = 0; gather$iK < gather$nK; gather$iK += 1)
//       if ($gather(category, P, dir, angle, gather$nK, gather$iK, pairs...)) stmt else stmt }
StmtPtr Parser::parseGather() {
    const SourceLoc loc = locOf(next());
    const std::string k = std::to_string(pos_);
    expect("(", "after 'gather'");
    auto call = std::make_unique<Expr>(ExprKind::Call, loc);
    call->text = "$gather";
    if (!isPunct(")")) {
        do {
            call->args.push_back(parseAssign());
        } while (accept(","));
    }
    expect(")", "after the arguments");
    if (call->args.size() < 5)
        throw InputError(loc, "gather takes (category, P, dir, angle, samples, \"surface:Ci\", variable, ..., options...)");
    auto name = [&](const std::string& n) {
        auto e = std::make_unique<Expr>(ExprKind::Name, loc);
        e->text = n;
        return e;
    };
    auto binary = [&](ExprKind kind, const char* op, ExprPtr a, ExprPtr b) {
        auto e = std::make_unique<Expr>(kind, loc);
        e->text = op;
        e->args.push_back(std::move(a));
        e->args.push_back(std::move(b));
        return e;
    };
    auto number = [&](double v) {
        auto e = std::make_unique<Expr>(ExprKind::Number, loc);
        e->number = v;
        return e;
    };
    const std::string n = "gather$n" + k, i = "gather$i" + k;
    auto block = std::make_unique<Stmt>(StmtKind::Block, loc);
    auto decl = std::make_unique<Stmt>(StmtKind::Decl, loc);
    decl->decl.loc = loc;
    decl->decl.base = BaseType::Float;
    decl->decl.hasDetail = true;
    decl->decl.detail = Detail::Uniform;
    decl->decl.decls.resize(2);
    decl->decl.decls[0].name = n;
    decl->decl.decls[0].loc = call->args[4]->loc;
    decl->decl.decls[0].init = std::move(call->args[4]);
    decl->decl.decls[1].name = i;
    decl->decl.decls[1].loc = loc;
    call->args[4] = name(n);
    call->args.insert(call->args.begin() + 5, name(i));
    block->body.push_back(std::move(decl));
    auto loop = std::make_unique<Stmt>(StmtKind::For, loc);
    loop->init = binary(ExprKind::Assign, "=", name(i), number(0));
    loop->expr = binary(ExprKind::Binary, "<", name(i), name(n));
    loop->step = binary(ExprKind::Assign, "+=", name(i), number(1));
    auto branch = std::make_unique<Stmt>(StmtKind::If, loc);
    branch->expr = std::move(call);
    branch->body.push_back(parseStatement());
    if (isIdent("else")) {
        next();
        branch->body.push_back(parseStatement());
    }
    loop->body.push_back(std::move(branch));
    block->body.push_back(std::move(loop));
    return block;
}

// illuminance([category,] P [, axis, angle]) stmt; illuminate(P [, axis, angle]) stmt;
// solar([axis, angle]) stmt. The argument counts are checked by the checker.
StmtPtr Parser::parseLightStatement(StmtKind kind) {
    auto s = std::make_unique<Stmt>(kind, locOf(next()));
    expect("(", "after the light statement's name");
    if (!isPunct(")")) {
        do {
            s->args.push_back(parseAssign());
        } while (accept(","));
    }
    expect(")", "after the arguments");
    s->body.push_back(parseStatement());
    return s;
}

// ---- Expressions ----------------------------------------------------------------------------

ExprPtr Parser::parseExpr() { return parseAssign(); }

ExprPtr Parser::parseAssign() {
    ExprPtr lhs = parseTernary();
    static const char* const ops[] = {"=", "+=", "-=", "*=", "/="};
    for (const char* op : ops) {
        if (isPunct(op)) {
            auto e = std::make_unique<Expr>(ExprKind::Assign, locOf(next()));
            e->text = op;
            e->args.push_back(std::move(lhs));
            e->args.push_back(parseAssign());
            return e;
        }
    }
    return lhs;
}

ExprPtr Parser::parseTernary() {
    ExprPtr c = parseBinary(0);
    if (!isPunct("?")) return c;
    auto e = std::make_unique<Expr>(ExprKind::Ternary, locOf(next()));
    e->args.push_back(std::move(c));
    e->args.push_back(parseAssign());
    expect(":", "in a conditional expression");
    e->args.push_back(parseTernary());
    return e;
}

// Binary operators, loosest first. The dot product binds tightest, as in RI Spec 3.2.
ExprPtr Parser::parseBinary(int level) {
    static const std::vector<std::vector<const char*>> levels = {
        {"||"}, {"&&"}, {"==", "!="}, {"<", ">", "<=", ">="}, {"+", "-"}, {"*", "/"}, {"^"}, {"."}};
    if (level == int(levels.size())) return parseUnary();
    ExprPtr lhs = parseBinary(level + 1);
    for (;;) {
        const char* found = nullptr;
        for (const char* op : levels[size_t(level)])
            if (isPunct(op)) found = op;
        if (!found) return lhs;
        auto e = std::make_unique<Expr>(ExprKind::Binary, locOf(next()));
        e->text = found;
        e->args.push_back(std::move(lhs));
        e->args.push_back(parseBinary(level + 1));
        lhs = std::move(e);
    }
}

ExprPtr Parser::parseUnary() {
    if (isPunct("-") || isPunct("!") || isPunct("+")) {
        Token op = next();
        ExprPtr arg = parseUnary();
        if (op.text == "+") return arg;
        auto e = std::make_unique<Expr>(ExprKind::Unary, locOf(op));
        e->text = op.text;
        e->args.push_back(std::move(arg));
        return e;
    }
    if (isPunct("++") || isPunct("--")) {  // ++x is x += 1
        Token op = next();
        auto e = std::make_unique<Expr>(ExprKind::Assign, locOf(op));
        e->text = op.text == "++" ? "+=" : "-=";
        e->args.push_back(parseUnary());
        auto one = std::make_unique<Expr>(ExprKind::Number, locOf(op));
        one->number = 1;
        e->args.push_back(std::move(one));
        return e;
    }
    // A typecast or a constructor: type ["space"] expr, e.g. color "hsv" (h, s, v), float noise(P).
    if (atTypeName()) {
        Token t = peek();
        BaseType b = parseBaseType();
        auto e = std::make_unique<Expr>(ExprKind::Cast, locOf(t));
        e->castType = SlType(b);
        if (peek().kind == TokenKind::String) e->text = next().text;
        e->args.push_back(parseUnary());
        return e;
    }
    return parsePostfix();
}

ExprPtr Parser::parsePostfix() {
    ExprPtr e = parsePrimary();
    for (;;) {
        if (isPunct("[")) {
            auto ix = std::make_unique<Expr>(ExprKind::Index, locOf(next()));
            ix->args.push_back(std::move(e));
            ix->args.push_back(parseExpr());
            expect("]", "after the index");
            e = std::move(ix);
        } else if (isPunct("++") || isPunct("--")) {  // x++ is x += 1 (its value is the new one)
            Token op = next();
            auto a = std::make_unique<Expr>(ExprKind::Assign, locOf(op));
            a->text = op.text == "++" ? "+=" : "-=";
            a->args.push_back(std::move(e));
            auto one = std::make_unique<Expr>(ExprKind::Number, locOf(op));
            one->number = 1;
            a->args.push_back(std::move(one));
            e = std::move(a);
        } else {
            return e;
        }
    }
}

ExprPtr Parser::parsePrimary() {
    const Token& t = peek();
    SourceLoc loc = locOf(t);
    if (t.kind == TokenKind::Number) {
        auto e = std::make_unique<Expr>(ExprKind::Number, loc);
        e->number = next().number;
        return e;
    }
    if (t.kind == TokenKind::String) {
        auto e = std::make_unique<Expr>(ExprKind::String, loc);
        e->text = next().text;
        while (peek().kind == TokenKind::String) e->text += next().text;  // "a" "b" is "ab"
        return e;
    }
    if (t.kind == TokenKind::Ident) {
        // surface(...) and displacement(...) in an expression are message-passing calls.
        const bool call = (t.text == "surface" || t.text == "displacement") && isPunct("(", 1);
        if (isKeyword(t.text) && !call) fail(t, "expected an expression");
        auto e = std::make_unique<Expr>(ExprKind::Name, loc);
        e->text = next().text;
        if (accept("(")) {
            e->kind = ExprKind::Call;
            if (!isPunct(")")) {
                do {
                    e->args.push_back(parseAssign());
                } while (accept(","));
            }
            expect(")", "after the arguments");
        }
        return e;
    }
    if (isPunct("(")) {
        next();
        ExprPtr first = parseExpr();
        if (accept(")")) return first;
        auto e = std::make_unique<Expr>(ExprKind::Tuple, loc);
        e->args.push_back(std::move(first));
        while (accept(",")) e->args.push_back(parseExpr());
        expect(")", "after the tuple");
        if (e->args.size() != 3 && e->args.size() != 16)
            throw InputError(loc, "a tuple has 3 values (color, point, vector, normal) or 16 (matrix), not " +
                                      std::to_string(e->args.size()));
        return e;
    }
    fail(t, "expected an expression");
}

}  // namespace streyes::sl
