// Recursive-descent parser of the Shading Language (RI Spec 3.2, chapters 11-15): one shader
// definition and any number of functions, with their statements and expressions.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "shade/sl/ast.h"
#include "shade/sl/lexer.h"

namespace streyes::sl {

// Parses the preprocessed `source`. Syntax errors throw InputError "file:line:col: ...".
Module parseShader(const PreprocessedSource& source);

class Parser {
  public:
    // `source`: the text the tokens' offsets are in (default values are kept as written).
    Parser(std::vector<Token> tokens, const std::string& source);
    Module parseModule();

  private:
    const Token& peek(int k = 0) const;
    Token next();
    bool isPunct(const char* p, int k = 0) const;
    bool isIdent(const char* name, int k = 0) const;
    bool accept(const char* p);
    void expect(const char* p, const char* what);
    std::string expectIdent(const char* what);
    static const SourceLoc& locOf(const Token& t) { return t.loc; }
    [[noreturn]] void fail(const Token& at, const std::string& what) const;

    bool atTypeName(int k = 0) const;
    bool atDeclStart() const;
    BaseType parseBaseType();
    void parseFunction(Module& m);
    void parseShaderDef(Module& m);
    std::vector<VarDecl> parseFormals();
    VarDecl parseDeclHead(bool formal);
    void parseDeclarators(VarDecl& d);

    StmtPtr parseStatement();
    StmtPtr parseBlock();
    StmtPtr parseIf();
    StmtPtr parseGather();
    StmtPtr parseLightStatement(StmtKind kind);

    ExprPtr parseExpr();
    ExprPtr parseAssign();
    ExprPtr parseTernary();
    ExprPtr parseBinary(int level);
    ExprPtr parseUnary();
    ExprPtr parsePostfix();
    ExprPtr parsePrimary();
    ExprPtr parseArrayInit();
    std::string textBetween(const Token& first, const Token& afterLast) const;

    std::vector<Token> toks_;
    size_t pos_ = 0;
    const std::string& source_;
};

}  // namespace streyes::sl
