// main.cpp: the rsl2cl command:
//   rsl2cl [-I DIR] [-D NAME[=VALUE]] [--color-samples N] [--info | --ast] [-o OUT] X.sl
// Without --info/--ast it writes the generated OpenCL C (see runtime/rsl_abi.h).
// exit 0 on success, 1 on compile errors, 2 on usage errors.
#include <cstdlib>
#include <fstream>
#include <iostream>

#include "compiler.h"
#include "emit_cl.h"

namespace {

void usage(std::ostream& os) {
    os << "usage: rsl2cl [-I DIR] [-D NAME[=VALUE]] [--color-samples N] [--info | --ast]\n"
          "              [-o OUT] shader.sl\n"
          "  --color-samples N  colours of N channels (1-15, rsl_abi.h COLOURS; default 3)\n"
          "  --info   print shader metadata (kind, parameters, globals, services)\n"
          "  --ast    print the typed syntax tree\n"
          "  -o OUT   write the output to OUT instead of standard output\n"
          "  (default: the shader compiled to OpenCL C; see rsl2cl/runtime/rsl_abi.h)\n";
}

}  // namespace

int main(int argc, char** argv) {
    rsl::PreprocessOptions pp;
    std::string input, output;
    bool info = false, ast = false;
    int colorSamples = 3;
    for (int i = 1; i < argc; ++i) {
        std::string a = argv[i];
        auto value = [&](const std::string& flag) -> std::string {
            if (a.size() > flag.size()) return a.substr(flag.size());
            if (i + 1 >= argc) {
                std::cerr << "rsl2cl: " << flag << " needs a value\n";
                std::exit(2);
            }
            return argv[++i];
        };
        if (a == "--info") info = true;
        else if (a == "--color-samples") {
            const std::string v = value("--color-samples");
            char* end = nullptr;
            const long n = std::strtol(v.c_str(), &end, 10);
            if (end == v.c_str() || *end != '\0' || n < 1 || n > 15) {
                std::cerr << "rsl2cl: --color-samples needs a number from 1 to 15, got '"
                          << v << "'\n";
                return 2;
            }
            colorSamples = int(n);
        } else if (a == "--ast")
            ast = true;
        else if (a == "-h" || a == "--help") {
            usage(std::cout);
            return 0;
        } else if (a.rfind("-I", 0) == 0) pp.includeDirs.push_back(value("-I"));
        else if (a.rfind("-D", 0) == 0) {
            std::string d = value("-D");
            size_t eq = d.find('=');
            if (eq == std::string::npos) pp.defines.emplace_back(d, "1");
            else pp.defines.emplace_back(d.substr(0, eq), d.substr(eq + 1));
        } else if (a.rfind("-o", 0) == 0) output = value("-o");
        else if (!a.empty() && a[0] == '-') {
            std::cerr << "rsl2cl: unknown option '" << a << "'\n";
            usage(std::cerr);
            return 2;
        } else if (!input.empty()) {
            std::cerr << "rsl2cl: only one input file may be given\n";
            return 2;
        } else {
            input = a;
        }
    }
    if (input.empty()) {
        std::cerr << "rsl2cl: no input file\n";
        usage(std::cerr);
        return 2;
    }
    rsl::Diagnostics diag(&std::cerr);
    rsl::Program prog;
    bool ok = rsl::compileFile(input, pp, prog, diag);
    if (!ok) {
        std::cerr << diag.errorCount() << " error(s) in " << input << "\n";
        return 1;
    }
    std::string text;
    if (ast) text += rsl::dumpAst(prog);
    if (info)
        for (const auto& sh : prog.shaders) text += rsl::formatInfo(rsl::collectInfo(*sh));
    if (!info && !ast) {
        for (const auto& sh : prog.shaders) {
            rsl::EmittedShader em = rsl::emitOpenCL(*sh, prog, diag, colorSamples);
            text += em.source;
        }
        if (diag.hasErrors()) {
            std::cerr << diag.errorCount() << " error(s) in " << input << "\n";
            return 1;
        }
    }
    if (output.empty()) {
        std::cout << text;
    } else {
        std::ofstream out(output);
        out << text;
        if (!out) {
            std::cerr << "rsl2cl: cannot write " << output << "\n";
            return 1;
        }
    }
    return 0;
}
