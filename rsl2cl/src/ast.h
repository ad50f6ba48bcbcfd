// ast.h: the abstract syntax tree of an RSL compilation unit. Every node carries its
// SourceLoc; the type checker fills in types, uniform/varying flags and the symbol,
// builtin or user function each name refers to. The code generator walks this tree.
#pragma once
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "diagnostics.h"
#include "types.h"

namespace rsl {

struct Expr;
struct Stmt;
struct FunctionDecl;
struct Builtin;
struct BuiltinSig;
using ExprPtr = std::unique_ptr<Expr>;
using StmtPtr = std::unique_ptr<Stmt>;

enum class ShaderKind { Surface, Light, Displacement, Volume, Imager };
const char* shaderKindName(ShaderKind k);

enum class Storage { Default, Uniform, Varying };

enum class SymbolKind { Global, Param, Local, Function };

// A named entity; owned by Program::symbols, referred to from the tree.
struct Symbol {
    std::string name;
    SymbolKind kind = SymbolKind::Local;
    TypeSpec type;
    bool varying = false;       // after inference
    bool explicitStorage = false;  // declared uniform/varying (not inferred)
    bool output = false;        // output parameter
    bool readOnly = false;      // globals the shader kind may not write
    SourceLoc loc;
    FunctionDecl* function = nullptr;  // SymbolKind::Function
};

enum class ExprKind {
    Number,   // number
    String,   // text
    Ident,    // text = name; symbol
    Unary,    // text = op ("-", "!"); args[0]
    Binary,   // text = op (+ - * / . ^ == != < > <= >= && ||); args[0], args[1]
    Ternary,  // args[0] ? args[1] : args[2]
    Assign,   // text = op (= += -= *= /=); args[0] = lvalue, args[1]
    Call,     // text = name; args; builtin+sig or function; channel (texture "x"[ch])
    Cast,     // castType, text = space name ("" if none); args[0]
    Tuple,    // (a, b, c) or 16 values: args; type from context
    Index,    // args[0][args[1]]
};

struct Expr {
    ExprKind kind;
    SourceLoc loc;
    std::string text;
    double number = 0;
    std::vector<ExprPtr> args;
    TypeSpec castType;  // Cast
    // Filled by the type checker:
    TypeSpec type;
    bool varying = false;
    Symbol* symbol = nullptr;              // Ident
    const Builtin* builtin = nullptr;      // Call of a builtin
    const BuiltinSig* sig = nullptr;       // the chosen overload
    FunctionDecl* function = nullptr;      // Call of a user function
    ExprPtr channel;                       // texture("map"[1], ...): the [1]

    Expr(ExprKind k, SourceLoc l) : kind(k), loc(std::move(l)) {}
};

// One declared variable or parameter.
struct VarDecl {
    SourceLoc loc;
    std::string name;
    TypeSpec type;
    Storage storage = Storage::Default;
    bool output = false;
    bool isExtern = false;
    ExprPtr init;  // initialiser / parameter default (may be null)
    Symbol* symbol = nullptr;
};

enum class StmtKind {
    Empty, Expr, Decl, Block, If, While, For, Break, Continue, Return,
    Illuminance,  // args: [category,] P [, axis, angle]; body
    Illuminate,   // args: P [, axis, angle]; body
    Solar,        // args: [axis, angle]; body
    Function,     // nested function definition: function
};

struct Stmt {
    StmtKind kind;
    SourceLoc loc;
    ExprPtr expr;                  // Expr, If/While/For condition, Return value
    std::vector<VarDecl> decls;    // Decl
    std::vector<StmtPtr> stmts;    // Block
    StmtPtr body;                  // While/For/If-then/light loops
    StmtPtr elseBody;              // If
    StmtPtr init;                  // For (Decl or Expr statement; may be null)
    ExprPtr step;                  // For (may be null)
    int level = 1;                 // Break/Continue
    std::vector<ExprPtr> args;     // Illuminance/Illuminate/Solar
    std::unique_ptr<FunctionDecl> function;  // Function
    Stmt(StmtKind k, SourceLoc l) : kind(k), loc(std::move(l)) {}
};

struct FunctionDecl {
    SourceLoc loc;
    std::string name;
    TypeSpec returnType;
    std::vector<VarDecl> params;
    StmtPtr body;  // a Block
    Symbol* symbol = nullptr;
    bool readsVarying = false;  // body reads a varying global/extern (type checker)
};

struct ShaderDecl {
    SourceLoc loc;
    ShaderKind kind;
    std::string name;
    std::vector<VarDecl> params;
    StmtPtr body;  // a Block
};

struct Program {
    std::vector<std::unique_ptr<FunctionDecl>> functions;  // top-level functions
    std::vector<std::unique_ptr<ShaderDecl>> shaders;
    std::deque<std::unique_ptr<Symbol>> symbols;           // every symbol
    Symbol* newSymbol() {
        symbols.push_back(std::make_unique<Symbol>());
        return symbols.back().get();
    }
};

// Writes the tree as indented text (used by `rsl2cl --ast` and tests).
std::string dumpAst(const Program& prog);
std::string exprToString(const Expr& e);  // RSL-like source of an expression

}  // namespace rsl
